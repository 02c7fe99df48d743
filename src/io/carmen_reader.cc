#include "fusemap/io/carmen_reader.h"

#include <deque>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "fusemap/io/lcm_conversions.h"

namespace fusemap {
namespace io {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Reads lines from a plain or gzip file (gzopen reads both transparently).
class LineReader {
 public:
  ~LineReader() { Close(); }
  bool Open(const std::string& path) {
    Close();
    file_ = gzopen(path.c_str(), "rb");
    return file_ != nullptr;
  }
  void Close() {
    if (file_ != nullptr) gzclose(file_);
    file_ = nullptr;
  }
  bool Rewind() { return gzrewind(file_) == 0; }
  // False at end of file. *complete is false for a last line without its newline.
  bool ReadLine(std::string* line, bool* complete) {
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
    return !line->empty();
  }

 private:
  gzFile file_ = nullptr;
};

// Splits in place: separators become '\0' and tokens point into `line`.
std::vector<char*> Tokenize(std::string* line) {
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

enum class MessageType { kOther, kOdom, kFlaser, kRobotLaser };

MessageType TypeOf(const char* tag) {
  if (std::strcmp(tag, "ODOM") == 0) return MessageType::kOdom;
  if (std::strcmp(tag, "FLASER") == 0) return MessageType::kFlaser;
  if (std::strcmp(tag, "ROBOTLASER1") == 0) return MessageType::kRobotLaser;
  return MessageType::kOther;
}

// The fields of one ODOM, FLASER or ROBOTLASER1 line that the reader uses.
struct ParsedMessage {
  MessageType type = MessageType::kOther;
  std::vector<float> ranges;
  std::vector<float> remissions;
  double start_angle_rad = 0.0, increment_rad = 0.0, max_range_m = 0.0;
  double pose[3] = {0.0, 0.0, 0.0};  // ODOM pose, or FLASER's (estimated) pose
  double velocity[2] = {0.0, 0.0};
  double accel = 0.0;  // ODOM only
  common::Rigid2d T_base_laser;
  double times[2] = {0.0, 0.0};  // timestamp, logger_timestamp
};

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

bool ParseMessage(const std::vector<char*>& tokens, bool complete, ParsedMessage* out,
                  std::string* reason) {
  const FieldParser f(tokens);
  out->type = TypeOf(tokens[0]);
  const size_t n_tok = tokens.size();
  switch (out->type) {
    case MessageType::kOdom: {
      // ODOM x y theta tv rv accel timestamp host logger_timestamp
      if (!f.Expect(10, complete, "ODOM x y theta tv rv accel ts host logger_ts", reason)) {
        return false;
      }
      for (int k = 0; k < 3; ++k) {
        if (!f.Number(1 + k, &out->pose[k], reason)) return false;
      }
      return f.Number(4, &out->velocity[0], reason) && f.Number(5, &out->velocity[1], reason) &&
             f.Number(6, &out->accel, reason) && f.Number(7, &out->times[0], reason) &&
             f.Number(9, &out->times[1], reason);
    }
    case MessageType::kFlaser: {
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
      return f.Number(2 + n + 6, &out->times[0], reason) &&
             f.Number(2 + n + 8, &out->times[1], reason);
    }
    case MessageType::kRobotLaser: {
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
      return f.Number(16 + n + m, &out->velocity[0], reason) &&
             f.Number(17 + n + m, &out->velocity[1], reason) &&
             f.Number(21 + n + m, &out->times[0], reason) &&
             f.Number(23 + n + m, &out->times[1], reason);
    }
    case MessageType::kOther:
      break;
  }
  return true;
}

// Statistics of one candidate time field over all timed lines, in file order.
struct TimeFieldStats {
  int n = 0, zeros = 0, invalid = 0, repeats = 0;
  double first = 0.0, last = 0.0, max_backward_s = 0.0;

  void Add(double t) {
    if (n == 0) first = t;
    if (n > 0) max_backward_s = std::max(max_backward_s, last - t);
    if (n > 0 && t == last) ++repeats;
    // Negative values and denormal-sized garbage (orebro's 1e-86) are not clock readings.
    if (t < 0.0 || (t != 0.0 && t < 1e-6)) ++invalid;
    if (t == 0.0) ++zeros;
    last = t;
    ++n;
  }
  // Empty if usable, else the reason it is not.
  std::string Problem(double reorder_window_s) const {
    if (n == 0) return "no timed lines";
    if (invalid > 0) return std::to_string(invalid) + " negative or garbage values";
    if (zeros > n / 100) return std::to_string(zeros) + "/" + std::to_string(n) + " zero";
    // A scan shares its stamp with the ODOM just before it; half the steps repeating is not that.
    if (repeats > n / 2) {
      return "too coarse (" + std::to_string(repeats) + " of " + std::to_string(n) +
             " values repeat the previous one)";
    }
    if (max_backward_s > reorder_window_s) {
      std::ostringstream s;
      s << "steps back by " << max_backward_s << " s";
      return s.str();
    }
    return "";
  }
};

// GMapping's gfs output interleaves its own pose estimates as ODOM lines: right after each
// FLASER (repeating that scan's pose) and, in orebro, after NEFF with zero time and motion.
// Neither is wheel odometry. Feed every non-empty line in order.
class GmappingPoseFilter {
 public:
  bool IsEstimate(const char* tag, const ParsedMessage* msg) {
    bool estimate = false;
    if (msg != nullptr && msg->type == MessageType::kOdom) {
      const bool repeats_scan = previous_ == Previous::kFlaser &&
                                std::equal(msg->pose, msg->pose + 3, flaser_pose_);
      const bool zero = msg->times[0] == 0.0 && msg->times[1] == 0.0 &&
                        msg->velocity[0] == 0.0 && msg->velocity[1] == 0.0 && msg->accel == 0.0;
      estimate = repeats_scan || (previous_ == Previous::kNeff && zero);
    }
    previous_ = std::strcmp(tag, "NEFF") == 0 ? Previous::kNeff : Previous::kOther;
    if (msg != nullptr && msg->type == MessageType::kFlaser) {
      previous_ = Previous::kFlaser;
      std::copy(msg->pose, msg->pose + 3, flaser_pose_);
    }
    return estimate;
  }

 private:
  enum class Previous { kOther, kFlaser, kNeff };
  Previous previous_ = Previous::kOther;
  double flaser_pose_[3] = {0.0, 0.0, 0.0};
};

struct Pending {
  double stamp_s;
  int64_t seq;
  CarmenRecord record;
};

}  // namespace

struct CarmenReader::Impl {
  std::string path;
  LineReader reader;
  std::string line;
  int line_no = 0;
  int time_field = -1;  // 0 timestamp, 1 logger_timestamp, -1 synthesized from line order
  int64_t seq = 0;
  GmappingPoseFilter gmapping_filter;
  // GMapping re-bases the ODOM stream onto its own estimate after every scan (the first ODOM
  // after a scan continues from the estimate, not from the previous ODOM). T_fix undoes each
  // jump so the output is the continuous, drifting wheel odometry and carries none of
  // GMapping's corrections: odometry_out = T_fix * odometry_in.
  common::Rigid2d T_fix;
  common::Rigid2d last_raw_odometry;
  bool have_raw_odometry = false;
  std::deque<Pending> pending;  // file order
  double newest_stamp_s = -INFINITY;
  double last_output_s = -INFINITY;
  bool at_eof = false;
};

bool CarmenOptions::IsValid(std::string* error) const {
  std::string reason;
  if (!(range_max_m >= 0.0)) reason = "range_max_m must be >= 0 (0 = automatic)";
  if (!(synthetic_period_s > 0.0)) reason = "synthetic_period_s must be > 0";
  if (!(reorder_window_s >= 0.0)) reason = "reorder_window_s must be >= 0";
  if (reason.empty()) return true;
  if (error != nullptr) *error = reason;
  return false;
}

CarmenOptions ParseCarmenOptions(common::ConfigReader& reader) {
  CarmenOptions options;
  reader.Get("skip_bad", &options.skip_bad);
  reader.Get("range_max_m", &options.range_max_m);
  reader.Get("synthetic_period_s", &options.synthetic_period_s);
  reader.Get("reorder_window_s", &options.reorder_window_s);
  reader.Get("drop_gmapping_poses", &options.drop_gmapping_poses);
  std::string error;
  if (!options.IsValid(&error)) reader.AddError("carmen", error);
  return options;
}

std::string CarmenSummary::ToString() const {
  std::ostringstream s;
  s << "scans=" << lasers << " odometry=" << odometry << " skipped=" << skipped_bad
    << " gmapping_poses_dropped=" << gmapping_poses_dropped << " odometry_rebases_undone=" << odometry_rebases_undone
    << " repaired_stamps=" << repaired_stamps
    << " clamped=" << clamped_stamps << " time_policy=" << time_policy << " ("
    << time_reason << ") range_max_m=" << range_max_m << " (" << range_max_source << ")"
    << " lines=" << lines << " types=";
  bool first = true;
  for (const auto& [type, count] : lines_by_type) {
    s << (first ? "" : ",") << type << ":" << count;
    first = false;
  }
  return s.str();
}

CarmenReader::CarmenReader(const CarmenOptions& options)
    : options_(options), impl_(std::make_unique<Impl>()) {}
CarmenReader::~CarmenReader() = default;

bool CarmenReader::Open(const std::string& path, std::string* error) {
  std::string reason;
  if (!options_.IsValid(&reason)) {
    *error = "invalid CARMEN options: " + reason;
    return false;
  }
  impl_ = std::make_unique<Impl>();
  impl_->path = path;
  summary_ = CarmenSummary();
  if (!impl_->reader.Open(path)) {
    *error = path + ": cannot open";
    return false;
  }
  // Pre-pass: time field statistics and the FLASER range histogram. Malformed lines are
  // ignored here; the main pass reports them.
  TimeFieldStats stats[2];
  std::map<float, int> range_counts;
  int64_t beams = 0;
  double param_range_max_m = 0.0;
  bool complete = false;
  GmappingPoseFilter gmapping_filter;
  while (impl_->reader.ReadLine(&impl_->line, &complete)) {
    std::vector<char*> tokens = Tokenize(&impl_->line);
    if (tokens.empty()) continue;
    if (std::strcmp(tokens[0], "PARAM") == 0 && tokens.size() >= 3 &&
        std::strstr(tokens[1], "front_laser_max") != nullptr) {
      param_range_max_m = std::atof(tokens[2]);
    }
    ParsedMessage msg;
    const bool ok = TypeOf(tokens[0]) != MessageType::kOther &&
                    ParseMessage(tokens, complete, &msg, &reason);
    const bool estimate = gmapping_filter.IsEstimate(tokens[0], ok ? &msg : nullptr);
    if (!ok || (estimate && options_.drop_gmapping_poses)) continue;
    stats[0].Add(msg.times[0]);
    stats[1].Add(msg.times[1]);
    if (msg.type == MessageType::kFlaser) {
      for (float r : msg.ranges) ++range_counts[r];
      beams += static_cast<int64_t>(msg.ranges.size());
    }
  }

  // Time policy: the sensor timestamp if usable, else the logger's, else line order.
  const std::string problems[2] = {stats[0].Problem(options_.reorder_window_s),
                                   stats[1].Problem(options_.reorder_window_s)};
  impl_->time_field = problems[0].empty() ? 0 : (problems[1].empty() ? 1 : -1);
  if (impl_->time_field >= 0) {
    const TimeFieldStats& s = stats[impl_->time_field];
    // Anything before ~1973 as UNIX time is a time since the start of the log.
    summary_.time_policy = s.first < 1e8 ? "relative" : "absolute";
    summary_.time_reason = impl_->time_field == 0 ? "timestamp" : "logger_timestamp";
    if (impl_->time_field == 1) summary_.time_reason += ", timestamp " + problems[0];
  } else {
    std::ostringstream s;
    s << "line order at " << options_.synthetic_period_s << " s per message; timestamp "
      << problems[0] << "; logger_timestamp " << problems[1];
    summary_.time_policy = "synthesized";
    summary_.time_reason = s.str();
  }

  // FLASER range limit: a maximum value that repeats is the sensor's "no return" reading;
  // nearby values within 0.2% (orebro: 32.759..32.767) belong to the same cluster.
  if (options_.range_max_m > 0.0) {
    summary_.range_max_m = options_.range_max_m;
    summary_.range_max_source = "option";
  } else if (!range_counts.empty()) {
    // Anchor at the highest value seen twice: a lone higher value is a real (rare) return.
    auto anchor = range_counts.rbegin();
    while (anchor != range_counts.rend() && anchor->second < 2) ++anchor;
    const double top = anchor == range_counts.rend() ? 0.0 : anchor->first;
    const double cluster_low = top - std::max(0.05, 0.002 * top);
    int in_cluster = 0;
    double lowest = top;
    for (auto it = anchor; it != range_counts.rend() && it->first >= cluster_low; ++it) {
      if (it->second < 2) continue;
      in_cluster += it->second;
      lowest = it->first;
    }
    if (in_cluster >= 3 && in_cluster >= beams / 1000) {
      summary_.range_max_m = lowest;
      summary_.range_max_source = "repeated_max";
    } else if (param_range_max_m > 0.0) {
      summary_.range_max_m = param_range_max_m;
      summary_.range_max_source = "param";
    } else {
      summary_.range_max_m = range_counts.rbegin()->first + 0.01;
      summary_.range_max_source = "max_seen";
    }
  } else {
    summary_.range_max_m = param_range_max_m > 0.0 ? param_range_max_m : 81.83;
    summary_.range_max_source = param_range_max_m > 0.0 ? "param" : "no_flaser";
  }

  if (!impl_->reader.Rewind()) {
    *error = path + ": cannot rewind";
    return false;
  }
  return true;
}

bool CarmenReader::Next(CarmenRecord* out, std::string* error) {
  error->clear();
  Impl& im = *impl_;
  bool complete = false;
  // Read ahead until every later line that could still have a smaller stamp than the oldest
  // pending one (within the window) is in memory.
  const double window_s = options_.reorder_window_s;
  while (!im.at_eof &&
         (im.pending.empty() || im.newest_stamp_s <= im.pending.front().stamp_s + window_s)) {
    if (!im.reader.ReadLine(&im.line, &complete)) {
      im.at_eof = true;
      break;
    }
    ++im.line_no;
    std::vector<char*> tokens = Tokenize(&im.line);
    if (tokens.empty()) continue;
    ++summary_.lines;
    ++summary_.lines_by_type[tokens[0]];
    ParsedMessage msg;
    std::string reason;
    if (TypeOf(tokens[0]) == MessageType::kOther) {
      im.gmapping_filter.IsEstimate(tokens[0], nullptr);
      continue;
    }
    if (!ParseMessage(tokens, complete, &msg, &reason)) {
      const std::string where = im.path + ":" + std::to_string(im.line_no) + ": " + reason;
      im.gmapping_filter.IsEstimate(tokens[0], nullptr);
      if (!options_.skip_bad) {
        *error = where;
        return false;
      }
      ++summary_.skipped_bad;
      if (summary_.first_skip_reasons.size() < 5) summary_.first_skip_reasons.push_back(where);
      continue;
    }
    if (im.gmapping_filter.IsEstimate(tokens[0], &msg) && options_.drop_gmapping_poses) {
      ++summary_.gmapping_poses_dropped;
      if (im.have_raw_odometry) {
        const common::Rigid2d estimate(msg.pose[0], msg.pose[1], msg.pose[2]);
        const common::Rigid2d jump = im.last_raw_odometry * estimate.inverse();
        if (jump.translation().norm() > 1e-9 || std::abs(jump.angle_rad()) > 1e-9) {
          ++summary_.odometry_rebases_undone;
        }
        im.T_fix = im.T_fix * jump;
        im.last_raw_odometry = estimate;
      }
      continue;
    }

    Pending p;
    p.seq = im.seq++;
    p.stamp_s = im.time_field >= 0 ? msg.times[im.time_field]
                                   : static_cast<double>(p.seq) * options_.synthetic_period_s;
    CarmenRecord& r = p.record;
    r.line = im.line_no;
    if (msg.type == MessageType::kOdom) {
      r.kind = CarmenRecord::Kind::kOdometry;
      const common::Rigid2d raw(msg.pose[0], msg.pose[1], msg.pose[2]);
      im.last_raw_odometry = raw;
      im.have_raw_odometry = true;
      r.odometry.pose = im.T_fix * raw;
      r.linear_velocity_mps = msg.velocity[0];
      r.angular_velocity_radps = msg.velocity[1];
    } else {
      r.kind = CarmenRecord::Kind::kLaser;
      r.scan.frame = "laser";
      r.scan.angle_min_rad = static_cast<float>(msg.start_angle_rad);
      r.scan.angle_increment_rad = static_cast<float>(msg.increment_rad);
      r.scan.range_min_m = 0.f;
      const bool use_line_max = msg.type == MessageType::kRobotLaser && msg.max_range_m > 0.0 &&
                                options_.range_max_m == 0.0;
      r.scan.range_max_m =
          static_cast<float>(use_line_max ? msg.max_range_m : summary_.range_max_m);
      r.scan.ranges_m = std::move(msg.ranges);
      r.scan.intensities = std::move(msg.remissions);
      r.T_base_laser = msg.T_base_laser;
    }
    im.newest_stamp_s = std::max(im.newest_stamp_s, p.stamp_s);
    im.pending.push_back(std::move(p));
  }
  if (im.pending.empty()) return false;

  Pending p = std::move(im.pending.front());
  im.pending.pop_front();
  double later_min_s = INFINITY;
  for (const Pending& later : im.pending) later_min_s = std::min(later_min_s, later.stamp_s);
  if (later_min_s < p.stamp_s) {
    p.stamp_s = later_min_s;
    ++summary_.repaired_stamps;
  }
  if (p.stamp_s < im.last_output_s) {
    p.stamp_s = im.last_output_s;
    ++summary_.clamped_stamps;
  }
  im.last_output_s = p.stamp_s;
  *out = std::move(p.record);
  if (out->kind == CarmenRecord::Kind::kLaser) {
    out->scan.stamp_s = p.stamp_s;
    ++summary_.lasers;
  } else {
    out->odometry.stamp_s = p.stamp_s;
    ++summary_.odometry;
  }
  return true;
}

}  // namespace io
}  // namespace fusemap
