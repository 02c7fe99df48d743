#include "fusemap/io/carmen_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <sstream>

#include "fusemap/io/lcm_conversions.h"
#include "carmen_line_parser.h"
#include "carmen_stamp_repair.h"

namespace fusemap {
namespace io {
namespace {

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

struct Pending {
  double stamp_s;
  int64_t seq;
  CarmenRecord record;
  // The stamp as printed, the width of its rounding interval, and whether the record happened
  // at a new instant rather than together with the record before it (see SpreadOverRounding).
  double printed_s = 0.0;
  double resolution_s = 0.0;
  bool starts_instant = true;
  bool spread = false;  // stamp_s already spread over the rounding interval
};

}  // namespace

struct CarmenReader::Impl {
  std::string path;
  CarmenLineReader reader;
  std::string line;
  int line_no = 0;
  int time_field = -1;  // 0 timestamp, 1 logger_timestamp, -1 synthesized from line order
  int64_t seq = 0;
  int64_t instant = -1;  // synthesized time: index of the instant of the last record
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
  bool last_kept_odometry = false;  // the last record queued was an ODOM line
};

namespace {

// Spreads the run of queued records, from the first, that print the same stamp (all of it is
// queued; see Next). Returns the run's length if it held more than one instant, else 0.
int SpreadFirstRun(std::deque<Pending>* pending) {
  if (pending->empty() || pending->front().spread) return 0;
  const double printed_s = pending->front().printed_s;
  std::vector<bool> starts_instant;
  for (const Pending& p : *pending) {
    if (p.spread || p.printed_s != printed_s) break;
    starts_instant.push_back(p.starts_instant);
  }
  const std::vector<double> stamps =
      SpreadOverRounding(printed_s, pending->front().resolution_s, starts_instant);
  int instants = 0;
  for (size_t i = 0; i < stamps.size(); ++i) {
    Pending& p = (*pending)[i];
    if (i == 0 || p.starts_instant) ++instants;
    p.stamp_s = stamps[i];
    p.spread = true;
  }
  return instants > 1 ? static_cast<int>(stamps.size()) : 0;
}

// Earliest time a queued record can have happened: its stamp once spread, else the start of
// its rounding interval.
double EarliestS(const Pending& p) {
  return p.spread ? p.stamp_s : p.printed_s - 0.5 * p.resolution_s;
}

// File order is the true order, so a front record stamped later than a record after it
// happened before that record. It and the late records right after it that wait for the same
// earlier stamp are placed evenly between the last output stamp and that stamp (instead of
// piling onto it). False if the front is not late.
bool LowerLateFront(const std::deque<Pending>& pending, double last_output_s,
                    double* stamp_s) {
  const size_t n = pending.size();
  if (n < 2) return false;
  // later_min[i]: the smallest EarliestS after record i.
  std::vector<double> later_min(n, INFINITY);
  for (size_t i = n - 1; i > 0; --i) {
    later_min[i - 1] = std::min(later_min[i], EarliestS(pending[i]));
  }
  const double target_s = later_min[0];
  if (!(target_s < pending[0].stamp_s)) return false;
  size_t late = 1;
  while (late < n && later_min[late] == target_s && EarliestS(pending[late]) > target_s) {
    ++late;
  }
  *stamp_s = target_s;
  if (std::isfinite(last_output_s) && last_output_s < target_s) {
    *stamp_s = last_output_s + (target_s - last_output_s) / static_cast<double>(late + 1);
  }
  return true;
}

}  // namespace

void CarmenOptions::Check(common::OptionChecker* check) const {
  check->Require(range_max_m >= 0.0, "range_max_m", "must be >= 0 (0 = automatic)");
  check->Require(synthetic_period_s > 0.0, "synthetic_period_s", "must be > 0");
  check->Require(reorder_window_s >= 0.0, "reorder_window_s", "must be >= 0");
}

bool CarmenOptions::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

CarmenOptions ParseCarmenOptions(common::ConfigReader& reader) {
  CarmenOptions options;
  reader.Get("skip_bad", &options.skip_bad);
  reader.Get("range_max_m", &options.range_max_m);
  reader.Get("synthetic_period_s", &options.synthetic_period_s);
  reader.Get("reorder_window_s", &options.reorder_window_s);
  reader.Get("drop_gmapping_poses", &options.drop_gmapping_poses);
  reader.CheckOptions(options);
  return options;
}

namespace {

// Printable ASCII as is; anything else (and the separators ',' ':' '\\') as \xHH; long tokens
// cut to 32 bytes.
std::string EscapedToken(const std::string& token) {
  std::string out;
  for (size_t i = 0; i < token.size() && i < 32; ++i) {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    if (c > 0x20 && c < 0x7f && c != ',' && c != ':' && c != '\\') {
      out += static_cast<char>(c);
    } else {
      char hex[5];
      std::snprintf(hex, sizeof(hex), "\\x%02x", c);
      out += hex;
    }
  }
  if (token.size() > 32) out += "...";
  return out;
}

}  // namespace

std::string CarmenSummary::ToString() const {
  std::ostringstream s;
  s << "scans=" << lasers << " odometry=" << odometry;
  // orebro: every ODOM line but the first (at the origin, at rest) is GMapping's estimate.
  if (lasers > 0 && odometry < 2) {
    s << " (NO WHEEL ODOMETRY: the ODOM lines are GMapping's pose estimates; map with"
         " local_slam.use_odometry: false)";
  }
  s << " skipped=" << skipped_bad
    << " gmapping_poses_dropped=" << gmapping_poses_dropped << " odometry_rebases_undone=" << odometry_rebases_undone
    << " spread_stamps=" << spread_stamps << " repaired_stamps=" << repaired_stamps
    << " clamped=" << clamped_stamps << " time_policy=" << time_policy << " ("
    << time_reason << ") range_max_m=" << range_max_m << " (" << range_max_source << ")"
    << " lines=" << lines << " types=";
  bool first = true;
  for (const auto& [type, count] : lines_by_type) {
    // The first token of a line of a binary file: shown, not printed raw.
    s << (first ? "" : ",") << EscapedToken(type) << ":" << count;
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
    *error = path + ": cannot open: " + impl_->reader.failure();
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
    std::vector<char*> tokens = TokenizeCarmenLine(&impl_->line);
    if (tokens.empty()) continue;
    if (std::strcmp(tokens[0], "PARAM") == 0 && tokens.size() >= 3 &&
        std::strstr(tokens[1], "front_laser_max") != nullptr) {
      param_range_max_m = std::atof(tokens[2]);
    }
    CarmenMessage msg;
    const bool ok = CarmenTypeOf(tokens[0]) != CarmenMessageType::kOther &&
                    ParseCarmenMessage(tokens, complete, &msg, &reason);
    const bool estimate = gmapping_filter.IsEstimate(tokens[0], ok ? &msg : nullptr);
    if (!ok || (estimate && options_.drop_gmapping_poses)) continue;
    stats[0].Add(msg.times[0]);
    stats[1].Add(msg.times[1]);
    if (msg.type == CarmenMessageType::kFlaser) {
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
    s << "line order at " << options_.synthetic_period_s
      << " s per instant, a scan sharing the stamp of the ODOM before it; timestamp "
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

  // The time statistics above left out every ODOM after NEFF with zero time and motion; with
  // an odometry stream those are readings (their stamps, all zero, change no time policy).
  impl_->gmapping_filter = GmappingPoseFilter(gmapping_filter.stream_odometry_lines() > 1);

  if (!impl_->reader.failure().empty() || !impl_->reader.Rewind()) {
    *error = path + ": " + impl_->reader.failure();
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
  // Also until the run of records printing the front's stamp is complete, so it can be spread.
  while (!im.at_eof &&
         (im.pending.empty() || im.newest_stamp_s <= im.pending.front().stamp_s + window_s ||
          (!im.pending.front().spread &&
           im.pending.back().printed_s == im.pending.front().printed_s))) {
    if (!im.reader.ReadLine(&im.line, &complete)) {
      im.at_eof = true;
      if (!im.reader.failure().empty()) {
        *error = im.path + ":" + std::to_string(im.line_no + 1) + ": " + im.reader.failure();
        return false;
      }
      break;
    }
    ++im.line_no;
    std::vector<char*> tokens = TokenizeCarmenLine(&im.line);
    if (tokens.empty()) continue;
    ++summary_.lines;
    ++summary_.lines_by_type[tokens[0]];
    CarmenMessage msg;
    std::string reason;
    if (CarmenTypeOf(tokens[0]) == CarmenMessageType::kOther) {
      im.gmapping_filter.IsEstimate(tokens[0], nullptr);
      continue;
    }
    if (!ParseCarmenMessage(tokens, complete, &msg, &reason)) {
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
    const bool gmapping_estimate = im.gmapping_filter.IsEstimate(tokens[0], &msg);
    if (gmapping_estimate && options_.drop_gmapping_poses) {
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
    // A scan happened with the ODOM line printed just before it, and GMapping's kept estimate
    // repeats the scan before it.
    p.starts_instant = !((msg.type != CarmenMessageType::kOdom && im.last_kept_odometry) ||
                         gmapping_estimate);
    im.last_kept_odometry = msg.type == CarmenMessageType::kOdom;
    // Synthesized time advances per instant, not per line: a scan stamped one period after
    // the ODOM taken with it would have the odometry extrapolated a whole step past the pose
    // the scan was taken at (csail: up to 0.3 rad and 0.25 m per step).
    if (p.starts_instant || im.instant < 0) ++im.instant;
    p.stamp_s = im.time_field >= 0 ? msg.times[im.time_field]
                                   : static_cast<double>(im.instant) * options_.synthetic_period_s;
    p.printed_s = p.stamp_s;
    if (im.time_field >= 0) {
      p.resolution_s = PrintedStampResolution(tokens[msg.time_tokens[im.time_field]]);
    }
    CarmenRecord& r = p.record;
    r.line = im.line_no;
    if (msg.type == CarmenMessageType::kOdom) {
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
      const bool use_line_max = msg.type == CarmenMessageType::kRobotLaser && msg.max_range_m > 0.0 &&
                                options_.range_max_m == 0.0;
      r.scan.range_max_m =
          static_cast<float>(use_line_max ? msg.max_range_m : summary_.range_max_m);
      r.scan.ranges_m = std::move(msg.ranges);
      r.scan.intensities = std::move(msg.remissions);
      r.T_base_laser = msg.T_base_laser;
      r.has_reference_pose = msg.type == CarmenMessageType::kFlaser;
      if (r.has_reference_pose) {
        r.reference_pose = common::Rigid2d(msg.pose[0], msg.pose[1], msg.pose[2]);
      }
    }
    im.newest_stamp_s = std::max(im.newest_stamp_s, p.stamp_s);
    im.pending.push_back(std::move(p));
  }
  if (im.pending.empty()) return false;

  summary_.spread_stamps += SpreadFirstRun(&im.pending);
  if (LowerLateFront(im.pending, im.last_output_s, &im.pending.front().stamp_s)) {
    ++summary_.repaired_stamps;
  }
  Pending p = std::move(im.pending.front());
  im.pending.pop_front();
  if (p.stamp_s < im.last_output_s) {
    p.stamp_s = im.last_output_s;
    ++summary_.clamped_stamps;
  }
  im.last_output_s = p.stamp_s;
  *out = std::move(p.record);
  out->log_stamp_s = im.time_field >= 0 ? p.printed_s : NAN;
  out->log_stamp_resolution_s = im.time_field >= 0 ? p.resolution_s : 0.0;
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
