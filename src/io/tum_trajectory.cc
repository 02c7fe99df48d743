#include "fusemap/io/tum_trajectory.h"

#include <cstdio>
#include <fstream>

#include "numeric_line_reader.h"
#include "write_all.h"

namespace fusemap {
namespace io {

bool ReadTumTrajectory(std::istream& in, const std::string& origin, eval::Trajectory* trajectory,
                       std::string* error) {
  trajectory->clear();
  NumericLineReader reader(in, origin, 8, "t x y z qx qy qz qw");
  std::vector<double> v;
  while (reader.Next(&v, error)) {
    const Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
    if (!(q.norm() > 1e-6)) return reader.Fail("quaternion has zero norm", error);
    if (!trajectory->empty() && !(v[0] > trajectory->back().stamp_s)) {
      char reason[160];
      std::snprintf(reason, sizeof(reason), "time %.6f does not increase (previous pose at %.6f)",
                    v[0], trajectory->back().stamp_s);
      return reader.Fail(reason, error);
    }
    trajectory->push_back(
        eval::TimedPose3d{v[0], common::Rigid3d(Eigen::Vector3d(v[1], v[2], v[3]), q)});
  }
  return error->empty();
}

bool ReadTumTrajectoryFile(const std::string& path, eval::Trajectory* trajectory,
                           std::string* error) {
  std::ifstream in(path);
  if (!in) {
    *error = path + ": cannot open for reading";
    return false;
  }
  return ReadTumTrajectory(in, path, trajectory, error);
}

bool WriteTumTrajectoryFile(const std::string& path, const eval::Trajectory& trajectory,
                            std::string* error) {
  std::string text = "# timestamp tx ty tz qx qy qz qw\n";
  char line[256];
  for (const eval::TimedPose3d& p : trajectory) {
    const Eigen::Vector3d& t = p.pose.translation();
    const Eigen::Quaterniond& q = p.pose.rotation();
    std::snprintf(line, sizeof(line), "%.6f %.9f %.9f %.9f %.9f %.9f %.9f %.9f\n", p.stamp_s,
                  t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w());
    text += line;
  }
  return WriteFileAtomically(path, text, error);
}

}  // namespace io
}  // namespace fusemap
