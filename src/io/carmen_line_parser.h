#ifndef FUSEMAP_IO_CARMEN_LINE_PARSER_H_
#define FUSEMAP_IO_CARMEN_LINE_PARSER_H_

#include <string>
#include <vector>

#include "fusemap/common/rigid_transform.h"

struct gzFile_s;

namespace fusemap {
namespace io {

// Reads lines from a plain or gzip file (gzopen reads both transparently).
class CarmenLineReader {
 public:
  CarmenLineReader() = default;
  ~CarmenLineReader();
  CarmenLineReader(const CarmenLineReader&) = delete;
  CarmenLineReader& operator=(const CarmenLineReader&) = delete;

  bool Open(const std::string& path);
  void Close();
  bool Rewind();
  // False at end of file or on a read error (then failure() says why). *complete is false for
  // a last line without its newline.
  bool ReadLine(std::string* line, bool* complete);
  // Why Open, ReadLine or Rewind failed ("is a directory", "corrupt gzip data: ..."); empty
  // after a clean end of file.
  const std::string& failure() const { return failure_; }

 private:
  void NoteFailure();

  gzFile_s* file_ = nullptr;
  std::string failure_;
};

// Splits in place: separators become '\0' and tokens point into `line`.
std::vector<char*> TokenizeCarmenLine(std::string* line);

enum class CarmenMessageType { kOther, kOdom, kFlaser, kRobotLaser };

CarmenMessageType CarmenTypeOf(const char* tag);

// The fields of one ODOM, FLASER or ROBOTLASER1 line that the reader uses.
struct CarmenMessage {
  CarmenMessageType type = CarmenMessageType::kOther;
  std::vector<float> ranges;
  std::vector<float> remissions;
  double start_angle_rad = 0.0, increment_rad = 0.0, max_range_m = 0.0;
  double pose[3] = {0.0, 0.0, 0.0};  // ODOM pose, or FLASER's (estimated) pose
  double velocity[2] = {0.0, 0.0};
  double accel = 0.0;  // ODOM only
  common::Rigid2d T_base_laser;
  double times[2] = {0.0, 0.0};  // timestamp, logger_timestamp
  size_t time_tokens[2] = {0, 0};  // where `times` were printed
};

// Parses an ODOM, FLASER or ROBOTLASER1 line (other tags: only out->type is set). False with
// a reason naming the field on a malformed or (complete = false) truncated line.
bool ParseCarmenMessage(const std::vector<char*>& tokens, bool complete, CarmenMessage* out,
                        std::string* reason);

// GMapping's gfs output interleaves its own pose estimates as ODOM lines: right after each
// FLASER, repeating that scan's pose, and, in a log without wheel odometry (orebro), after some
// NEFF lines with zero time and motion. Neither is wheel odometry. In a log with an odometry
// stream the ODOM after NEFF is that stream's next reading, even where every line has zero
// time and motion (freiburg-campus); dropping it loses a step of odometry per scan. Feed every
// non-empty line in order.
class GmappingPoseFilter {
 public:
  // has_odometry_stream: the log has ODOM lines besides the ones right after FLASER or NEFF
  // (see stream_odometry_lines(), counted by a first pass over the log).
  explicit GmappingPoseFilter(bool has_odometry_stream = false)
      : has_odometry_stream_(has_odometry_stream) {}

  // msg: the parsed line, or nullptr for other and malformed lines.
  bool IsEstimate(const char* tag, const CarmenMessage* msg);
  // ODOM lines seen so far right after neither a FLASER nor a NEFF line. A log without
  // wheel odometry has at most one (orebro: the robot at rest before the first scan).
  int stream_odometry_lines() const { return stream_odometry_lines_; }

 private:
  enum class Previous { kOther, kFlaser, kNeff };
  bool has_odometry_stream_;
  Previous previous_ = Previous::kOther;
  double flaser_pose_[3] = {0.0, 0.0, 0.0};
  int stream_odometry_lines_ = 0;
};

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_CARMEN_LINE_PARSER_H_
