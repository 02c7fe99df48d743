#include "fusemap/io/tum_trajectory.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace fusemap {
namespace io {
namespace {

bool Fail(const std::string& origin, int line_number, const std::string& reason,
          std::string* error) {
  *error = origin + ":" + std::to_string(line_number) + ": " + reason;
  return false;
}

}  // namespace

bool ReadTumTrajectory(std::istream& in, const std::string& origin, eval::Trajectory* trajectory,
                       std::string* error) {
  trajectory->clear();
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    double v[8];
    int count = 0;
    std::string token;
    while (fields >> token) {
      if (count == 8) return Fail(origin, line_number, "more than 8 fields", error);
      char* end = nullptr;
      v[count] = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0') {
        return Fail(origin, line_number,
                    "field " + std::to_string(count + 1) + " '" + token + "' is not a number",
                    error);
      }
      if (!std::isfinite(v[count])) {
        return Fail(origin, line_number, "field " + std::to_string(count + 1) + " is not finite",
                    error);
      }
      ++count;
    }
    if (count != 8) {
      return Fail(origin, line_number,
                  "expected 8 fields 't x y z qx qy qz qw', got " + std::to_string(count), error);
    }
    const Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
    if (!(q.norm() > 1e-6)) return Fail(origin, line_number, "quaternion has zero norm", error);
    if (!trajectory->empty() && !(v[0] > trajectory->back().stamp_s)) {
      char reason[160];
      std::snprintf(reason, sizeof(reason), "time %.6f does not increase (previous pose at %.6f)",
                    v[0], trajectory->back().stamp_s);
      return Fail(origin, line_number, reason, error);
    }
    trajectory->push_back(
        eval::TimedPose3d{v[0], common::Rigid3d(Eigen::Vector3d(v[1], v[2], v[3]), q)});
  }
  if (in.bad()) return Fail(origin, line_number, "read error", error);
  return true;
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
  std::FILE* file = std::fopen(path.c_str(), "w");
  if (file == nullptr) {
    *error = path + ": cannot open for writing";
    return false;
  }
  std::fprintf(file, "# timestamp tx ty tz qx qy qz qw\n");
  for (const eval::TimedPose3d& p : trajectory) {
    const Eigen::Vector3d& t = p.pose.translation();
    const Eigen::Quaterniond& q = p.pose.rotation();
    std::fprintf(file, "%.6f %.9f %.9f %.9f %.9f %.9f %.9f %.9f\n", p.stamp_s, t.x(), t.y(), t.z(),
                 q.x(), q.y(), q.z(), q.w());
  }
  const bool ok = std::fflush(file) == 0 && !std::ferror(file);
  if (std::fclose(file) != 0 || !ok) {
    *error = path + ": write failed";
    return false;
  }
  return true;
}

}  // namespace io
}  // namespace fusemap
