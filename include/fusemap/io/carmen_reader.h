#ifndef FUSEMAP_IO_CARMEN_READER_H_
#define FUSEMAP_IO_CARMEN_READER_H_

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "fusemap/common/config_reader.h"
#include "fusemap/common/rigid_transform.h"
#include "fusemap/sensor/sensor_types.h"

namespace fusemap {
namespace io {

struct CarmenOptions {
  // Skip and count malformed lines instead of failing on the first one.
  bool skip_bad = false;
  // FLASER "no return" threshold; 0 = automatic (repeated maximum value, else PARAM
  // *front_laser_max, else the largest value seen + 1 cm, i.e. every beam is a return).
  double range_max_m = 0.0;
  // Time step between consecutive messages when the log's timestamps are unusable.
  double synthetic_period_s = 0.1;
  // Records keep file order, which is the order things happened: in GMapping's logs the poses
  // are smooth in file order while some stamps are not (printed with 6 significant digits,
  // and some lines carry a late stamp). Runs of records printing one rounded stamp are spread
  // over its rounding interval (carmen_stamp_repair.h). A stamp larger than one that follows
  // it within this window is lowered: the late records are placed evenly between the previous
  // output stamp and the earliest later one. Larger backward steps make the timestamps count
  // as unusable.
  double reorder_window_s = 2.0;
  // Drop the ODOM line GMapping writes right after each FLASER repeating that scan's pose:
  // it is the filter's estimate, not wheel odometry.
  bool drop_gmapping_poses = true;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

CarmenOptions ParseCarmenOptions(common::ConfigReader& reader);

struct CarmenRecord {
  enum class Kind { kLaser, kOdometry };
  Kind kind = Kind::kOdometry;
  int line = 0;  // 1-based line in the file
  // The stamp as the log printed it, before spreading and repair, and the width of its
  // rounding interval; NaN and 0 when the time is synthesized. Ground truth taken from the
  // raw log is on this clock (see eval::StampMap).
  double log_stamp_s = 0.0;
  double log_stamp_resolution_s = 0.0;
  // kLaser: beams in the laser frame; stamp_s is the output time.
  sensor::LaserScan scan;
  // kLaser from FLASER: GMapping's pose estimate for this scan (the x y theta right after the
  // ranges). A reference layout to score against, never an input to the SLAM.
  bool has_reference_pose = false;
  common::Rigid2d reference_pose;
  common::Rigid2d T_base_laser;  // from ROBOTLASER1's laser and robot poses; identity for FLASER
  // kOdometry: raw wheel odometry with its measured velocities.
  sensor::OdometryData odometry;
  double linear_velocity_mps = 0.0;
  double angular_velocity_radps = 0.0;
};

// What the reader found and assumed; filled by Open() (policies) and Next() (counts).
struct CarmenSummary {
  int lines = 0;
  std::map<std::string, int> lines_by_type;  // first token of every non-empty line
  int lasers = 0;
  int odometry = 0;
  int skipped_bad = 0;
  std::vector<std::string> first_skip_reasons;  // up to 5, "file:line: reason"
  int gmapping_poses_dropped = 0;
  // Jumps of the ODOM stream onto GMapping's estimate after a scan, removed (see the reader).
  int odometry_rebases_undone = 0;
  // Stamps of records that printed the same rounded stamp, spread over its rounding interval.
  int spread_stamps = 0;
  int repaired_stamps = 0;  // late stamps lowered below a later line's smaller one
  int clamped_stamps = 0;  // records whose stamp was raised to the previous output stamp
  std::string time_policy;  // "relative", "absolute" or "synthesized"
  std::string time_reason;  // which field and why
  double range_max_m = 0.0;
  std::string range_max_source;  // "option", "repeated_max", "param", "max_seen"

  // One line: key=value pairs for logs and tools.
  std::string ToString() const;
};

// Streaming reader for CARMEN text logs (plain or gzip), producing laser scans (FLASER,
// ROBOTLASER1) and odometry (ODOM) with strictly non-decreasing stamps in output order.
// Open() makes one quick pre-pass over the file to choose the time policy and the FLASER range
// limit, so that every record is interpreted the same way; both are reported in summary().
class CarmenReader {
 public:
  explicit CarmenReader(const CarmenOptions& options);
  ~CarmenReader();
  CarmenReader(const CarmenReader&) = delete;
  CarmenReader& operator=(const CarmenReader&) = delete;

  bool Open(const std::string& path, std::string* error);
  // False at the end of the log (error left empty) or on a malformed line without skip_bad
  // (error = "file:line: reason").
  bool Next(CarmenRecord* out, std::string* error);
  const CarmenSummary& summary() const { return summary_; }

 private:
  struct Impl;
  CarmenOptions options_;
  CarmenSummary summary_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_CARMEN_READER_H_
