#ifndef FUSEMAP_SENSOR_SENSOR_TYPES_H_
#define FUSEMAP_SENSOR_SENSOR_TYPES_H_

#include <Eigen/Core>
#include <string>
#include <vector>

#include "fusemap/common/rigid_transform.h"

namespace fusemap {
namespace sensor {

// One sweep of a planar range finder, in its own frame (x forward, y left). Beam i points at
// angle_min_rad + i * angle_increment_rad. A range outside [range_min_m, range_max_m) is "no
// return" (the beam saw free space up to at least range_max_m, or nothing usable).
struct LaserScan {
  double stamp_s = 0.0;
  std::string frame = "laser";
  float angle_min_rad = 0.f;
  float angle_increment_rad = 0.f;
  float range_min_m = 0.f;
  float range_max_m = 0.f;
  std::vector<float> ranges_m;
  std::vector<float> intensities;  // empty or one per range
};

// A wheel-odometry pose of the robot base in the odometry frame (drifts; only increments count).
struct OdometryData {
  double stamp_s = 0.0;
  common::Rigid2d pose;
};

// Body-frame IMU sample.
struct ImuData {
  double stamp_s = 0.0;
  Eigen::Vector3d linear_acceleration_mps2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity_radps = Eigen::Vector3d::Zero();
};

// Points of one scan in some 2D frame: `origin` is the sensor position, `returns` the points
// that hit something, `misses` the ends of rays that saw nothing up to the cut-off length.
struct RangeData {
  Eigen::Vector2f origin = Eigen::Vector2f::Zero();
  std::vector<Eigen::Vector2f> returns;
  std::vector<Eigen::Vector2f> misses;
};

using PointCloud2d = std::vector<Eigen::Vector2f>;

// Transforms every point of `range_data` by `T_b_a`, giving the same data in frame b.
RangeData TransformRangeData(const RangeData& range_data, const common::Rigid2d& T_b_a);

}  // namespace sensor
}  // namespace fusemap

#endif  // FUSEMAP_SENSOR_SENSOR_TYPES_H_
