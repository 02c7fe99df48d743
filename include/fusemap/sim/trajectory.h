#ifndef FUSEMAP_SIM_TRAJECTORY_H_
#define FUSEMAP_SIM_TRAJECTORY_H_

#include <vector>

#include "fusemap/common/rigid_transform.h"
#include "fusemap/sim/world.h"

namespace fusemap {
namespace sim {

// The true planar motion of the robot base at one instant (world frame pose; body-frame
// forward speed, yaw rate and forward acceleration).
struct RobotState {
  common::Rigid2d T_world_base;
  double speed_mps = 0.0;
  double yaw_rate_radps = 0.0;
  double forward_accel_mps2 = 0.0;
};

// A smooth drive around a closed waypoint loop: corners are replaced by circular arcs tangent to
// both legs, and the speed profile respects the maximum speed, the tangential acceleration limit
// and the lateral acceleration limit v^2 * curvature <= a_lat (forward-backward pass over the
// path). The robot starts and ends at rest on the first leg, just past the first waypoint's arc.
class WaypointTrajectory {
 public:
  // plan.waypoints_m needs >= 3 distinct points (asserted; validate plans at the edge).
  explicit WaypointTrajectory(const RobotPlan& plan);

  double duration_s() const { return stamps_s_.empty() ? 0.0 : stamps_s_.back(); }
  double loop_length_m() const { return loop_length_m_; }
  // Clamped to [0, duration_s()].
  RobotState StateAt(double stamp_s) const;
  // When the robot has driven `laps` times the loop length (clamped to the drive).
  double TimeAtLaps(double laps) const;

 private:
  struct Piece {
    Eigen::Vector2d start;
    double heading_rad = 0.0;
    double length_m = 0.0;
    double curvature = 0.0;
  };
  // Position, heading and curvature at arc length s along the loop (wrapped).
  void Geometry(double s_m, Eigen::Vector2d* position, double* heading_rad,
                double* curvature) const;

  std::vector<Piece> pieces_;
  double loop_length_m_ = 0.0;
  double ds_m_ = 0.02;
  std::vector<double> speeds_mps_;  // At s = i * ds_m_.
  std::vector<double> stamps_s_;
};

}  // namespace sim
}  // namespace fusemap

#endif  // FUSEMAP_SIM_TRAJECTORY_H_
