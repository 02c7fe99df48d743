#include "carmen_line_parser.h"

#include <sys/stat.h>
#include <zlib.h>

#include <cerrno>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "fusemap/io/lcm_conversions.h"

namespace fusemap {
namespace io {
namespace {

constexpr double kPi = 3.14159265358979323846;

class FieldParser {
 public:
  explicit FieldParser(const std::vector<char*>& tokens) : tokens_(tokens) {}
  bool Number(size_t i, double* value, std::string* reason) const {
    char* end = nullptr;
    *value = std::strtod(tokens_[i], &end);
    if (end == tokens_[i] || *end != '\0' || !std::isfinite(*value)) {
      *reason = "non-numeric field " + std::to_string(i) + " '" + tokens_[i] + "'";
      return false;
    }
    return true;
  }
  bool Count(size_t i, const char* what, int* value, std::string* reason) const {
    double v = 0.0;
    if (!Number(i, &v, reason)) return false;
    if (v != std::floor(v) || v < 0 || v > kMaxLaserBeams) {
      *reason = std::string("absurd ") + what + " " + tokens_[i];
      return false;
    }
    *value = static_cast<int>(v);
    return true;
  }
  bool Floats(size_t first, int n, std::vector<float>* out, std::string* reason) const {
    out->resize(n);
    for (int k = 0; k < n; ++k) {
      double v = 0.0;
      if (!Number(first + k, &v, reason)) return false;
      (*out)[k] = static_cast<float>(v);
    }
    return true;
  }
  bool Expect(size_t n, bool complete, const std::string& layout, std::string* reason) const {
    if (tokens_.size() == n) return true;
    *reason = (complete ? std::string("field count does not match ") : "truncated line: ") +
              layout + ": expected " + std::to_string(n) + " fields, found " +
              std::to_string(tokens_.size());
    return false;
  }

 private:
  const std::vector<char*>& tokens_;
};

}  // namespace

CarmenLineReader::~CarmenLineReader() { Close(); }

bool CarmenLineReader::Open(const std::string& path) {
  Close();
  failure_.clear();
  struct stat info;
  if (::stat(path.c_str(), &info) != 0) {
    failure_ = std::strerror(errno);
    return false;
  }
  if (S_ISDIR(info.st_mode)) {
    failure_ = "is a directory, not a log file";
    return false;
  }
  file_ = gzopen(path.c_str(), "rb");
  if (file_ == nullptr) failure_ = std::strerror(errno);
  return file_ != nullptr;
}

void CarmenLineReader::NoteFailure() {
  int code = Z_OK;
  const char* message = gzerror(file_, &code);
  if (code == Z_ERRNO) {
    failure_ = std::string("read failed: ") + std::strerror(errno);
  } else if (code != Z_OK) {
    // Z_BUF_ERROR at the end: the gzip stream stops mid-way (truncated download).
    failure_ = std::string(code == Z_BUF_ERROR ? "truncated gzip data: " : "corrupt gzip data: ") +
               (message != nullptr ? message : "?");
  }
}

void CarmenLineReader::Close() {
  if (file_ != nullptr) gzclose(file_);
  file_ = nullptr;
}

bool CarmenLineReader::Rewind() {
  if (gzrewind(file_) == 0) return true;
  if (failure_.empty()) NoteFailure();
  if (failure_.empty()) failure_ = "cannot rewind (not a seekable file)";
  return false;
}

bool CarmenLineReader::ReadLine(std::string* line, bool* complete) {
  line->clear();
  char buffer[65536];
  while (gzgets(file_, buffer, sizeof(buffer)) != nullptr) {
    line->append(buffer);
    if (!line->empty() && line->back() == '\n') {
      *complete = true;
      return true;
    }
  }
  *complete = false;
  if (line->empty()) NoteFailure();
  return !line->empty();
}

std::vector<char*> TokenizeCarmenLine(std::string* line) {
  std::vector<char*> tokens;
  char* p = line->data();
  while (*p != '\0') {
    while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n') *p++ = '\0';
    if (*p == '\0') break;
    tokens.push_back(p);
    while (*p != '\0' && *p != ' ' && *p != '\t' && *p != '\r' && *p != '\n') ++p;
  }
  return tokens;
}

CarmenMessageType CarmenTypeOf(const char* tag) {
  if (std::strcmp(tag, "ODOM") == 0) return CarmenMessageType::kOdom;
  if (std::strcmp(tag, "FLASER") == 0) return CarmenMessageType::kFlaser;
  if (std::strcmp(tag, "ROBOTLASER1") == 0) return CarmenMessageType::kRobotLaser;
  return CarmenMessageType::kOther;
}

bool ParseCarmenMessage(const std::vector<char*>& tokens, bool complete, CarmenMessage* out,
                  std::string* reason) {
  const FieldParser f(tokens);
  out->type = CarmenTypeOf(tokens[0]);
  const size_t n_tok = tokens.size();
  switch (out->type) {
    case CarmenMessageType::kOdom: {
      // ODOM x y theta tv rv accel timestamp host logger_timestamp
      if (!f.Expect(10, complete, "ODOM x y theta tv rv accel ts host logger_ts", reason)) {
        return false;
      }
      for (int k = 0; k < 3; ++k) {
        if (!f.Number(1 + k, &out->pose[k], reason)) return false;
      }
      out->time_tokens[0] = 7;
      out->time_tokens[1] = 9;
      return f.Number(4, &out->velocity[0], reason) && f.Number(5, &out->velocity[1], reason) &&
             f.Number(6, &out->accel, reason) && f.Number(7, &out->times[0], reason) &&
             f.Number(9, &out->times[1], reason);
    }
    case CarmenMessageType::kFlaser: {
      // FLASER N r0..rN-1 x y theta odom_x odom_y odom_theta timestamp host logger_timestamp
      int n = 0;
      if (n_tok < 2) return f.Expect(2, complete, "FLASER N ...", reason);
      if (!f.Count(1, "beam count", &n, reason)) return false;
      if (n < 2) {
        *reason = "absurd beam count " + std::to_string(n);
        return false;
      }
      if (!f.Expect(n + 11, complete, "FLASER beam count N=" + std::to_string(n), reason) ||
          !f.Floats(2, n, &out->ranges, reason)) {
        return false;
      }
      // GMapping's convention (gfs2rec): 180/181 beams at 1 deg, 360/361 at 0.5 deg, from
      // -90 deg. Generalised: an odd N spans [-90, +90] inclusive, an even N [-90, +90).
      out->start_angle_rad = -kPi / 2.0;
      out->increment_rad = kPi / static_cast<double>(n - n % 2);
      for (int k = 0; k < 3; ++k) {
        if (!f.Number(2 + n + k, &out->pose[k], reason)) return false;
      }
      out->time_tokens[0] = 2 + n + 6;
      out->time_tokens[1] = 2 + n + 8;
      return f.Number(2 + n + 6, &out->times[0], reason) &&
             f.Number(2 + n + 8, &out->times[1], reason);
    }
    case CarmenMessageType::kRobotLaser: {
      // ROBOTLASER1 type start fov res max_range accuracy remission_mode N r.. M rem..
      //   laser_x laser_y laser_theta robot_x robot_y robot_theta tv rv fwd side turn_axis
      //   timestamp host logger_timestamp
      int n = 0, m = 0;
      if (n_tok < 10) return f.Expect(10, complete, "ROBOTLASER1 header", reason);
      double fov = 0.0;
      if (!f.Number(2, &out->start_angle_rad, reason) || !f.Number(3, &fov, reason) ||
          !f.Number(4, &out->increment_rad, reason) || !f.Number(5, &out->max_range_m, reason) ||
          !f.Count(8, "beam count", &n, reason)) {
        return false;
      }
      if (n_tok < static_cast<size_t>(n) + 10) {
        return f.Expect(n + 10, complete, "ROBOTLASER1 beam count", reason);
      }
      if (!f.Count(9 + n, "remission count", &m, reason)) return false;
      if (m != 0 && m != n) {
        *reason = "remission count " + std::to_string(m) + " is neither 0 nor " +
                  std::to_string(n);
        return false;
      }
      if (!f.Expect(n + m + 24, complete, "ROBOTLASER1 counts", reason) ||
          !f.Floats(9, n, &out->ranges, reason) ||
          !f.Floats(10 + n, m, &out->remissions, reason)) {
        return false;
      }
      double p[6];
      for (int k = 0; k < 6; ++k) {
        if (!f.Number(10 + n + m + k, &p[k], reason)) return false;
      }
      out->T_base_laser =
          common::Rigid2d(p[3], p[4], p[5]).inverse() * common::Rigid2d(p[0], p[1], p[2]);
      out->time_tokens[0] = 21 + n + m;
      out->time_tokens[1] = 23 + n + m;
      return f.Number(16 + n + m, &out->velocity[0], reason) &&
             f.Number(17 + n + m, &out->velocity[1], reason) &&
             f.Number(21 + n + m, &out->times[0], reason) &&
             f.Number(23 + n + m, &out->times[1], reason);
    }
    case CarmenMessageType::kOther:
      break;
  }
  return true;
}

bool GmappingPoseFilter::IsEstimate(const char* tag, const CarmenMessage* msg) {
  bool estimate = false;
  if (msg != nullptr && msg->type == CarmenMessageType::kOdom) {
    const bool repeats_scan = previous_ == Previous::kFlaser &&
                              std::equal(msg->pose, msg->pose + 3, flaser_pose_);
    const bool zero = msg->times[0] == 0.0 && msg->times[1] == 0.0 &&
                      msg->velocity[0] == 0.0 && msg->velocity[1] == 0.0 && msg->accel == 0.0;
    estimate = repeats_scan || (previous_ == Previous::kNeff && zero && !has_odometry_stream_);
    if (previous_ == Previous::kOther) ++stream_odometry_lines_;
  }
  previous_ = std::strcmp(tag, "NEFF") == 0 ? Previous::kNeff : Previous::kOther;
  if (msg != nullptr && msg->type == CarmenMessageType::kFlaser) {
    previous_ = Previous::kFlaser;
    std::copy(msg->pose, msg->pose + 3, flaser_pose_);
  }
  return estimate;
}

}  // namespace io
}  // namespace fusemap
