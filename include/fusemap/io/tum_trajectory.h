#ifndef FUSEMAP_IO_TUM_TRAJECTORY_H_
#define FUSEMAP_IO_TUM_TRAJECTORY_H_

#include <istream>
#include <string>

#include "fusemap/eval/trajectory.h"

namespace fusemap {
namespace io {

// TUM RGB-D benchmark trajectory format: one pose per line, `t x y z qx qy qz qw` (seconds,
// metres, unit quaternion of T_world_body), '#' starts a comment line, blank lines ignored.
// The reader requires exactly 8 finite numbers per line, a quaternion of non-zero norm (it is
// normalised) and strictly increasing time; on failure it returns false and names
// `origin:line: reason` in *error.
bool ReadTumTrajectory(std::istream& in, const std::string& origin, eval::Trajectory* trajectory,
                       std::string* error);
bool ReadTumTrajectoryFile(const std::string& path, eval::Trajectory* trajectory,
                           std::string* error);

// Writes with enough digits (stamps to 1 µs of absolute UNIX time, poses to 1e-9) to round-trip.
bool WriteTumTrajectoryFile(const std::string& path, const eval::Trajectory& trajectory,
                            std::string* error);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_TUM_TRAJECTORY_H_
