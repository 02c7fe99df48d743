#ifndef FUSEMAP_VISUAL_LOOP_PLANAR_CONSTRAINT_H_
#define FUSEMAP_VISUAL_LOOP_PLANAR_CONSTRAINT_H_

#include <string>

#include <Eigen/Core>

#include "fusemap/common/rigid_transform.h"
#include "fusemap/visual_loop/pose_covariance.h"

namespace fusemap {
namespace visual_loop {

struct PlanarConstraintOptions {
  // Both robot bases stand on the same floor: the verified motion between them must be nearly
  // planar. Beyond these it is a wrong match (or the floor is not flat) and is refused.
  double max_roll_pitch_rad = 0.05;  // ~3 degrees
  double max_height_m = 0.10;
  bool IsValid(std::string* error) const;
};

struct PlanarConstraint {
  bool accepted = false;
  std::string reason;  // why refused (empty when accepted)
  common::Rigid2d T_base_a_base_b;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();  // of (x, y, yaw)
  double roll_rad = 0.0;   // of T_base_a_base_b: what the planar projection drops
  double pitch_rad = 0.0;
  double height_m = 0.0;
};

// The 3D pose of base b in base a implied by a camera-to-camera transform and the cameras'
// mounts (T_base_camera; the same for one robot but kept apart for a changed mount).
common::Rigid3d BaseToBase(const common::Rigid3d& T_camera_a_camera_b,
                           const common::Rigid3d& T_base_camera_a,
                           const common::Rigid3d& T_base_camera_b);

// The 2D relative pose between two robot bases from a verified camera-to-camera transform with
// its 6x6 covariance (PerturbRight convention), through the camera extrinsics: x, y, yaw of
// T_base_a_base_b and their 3x3 covariance by first-order propagation; refused with a reason
// when roll, pitch or height disagree with a flat floor.
PlanarConstraint ToPlanarConstraint(const common::Rigid3d& T_camera_a_camera_b,
                                    const Matrix6d& covariance_camera,
                                    const common::Rigid3d& T_base_camera_a,
                                    const common::Rigid3d& T_base_camera_b,
                                    const PlanarConstraintOptions& options);

// Roll, pitch, yaw (rotation = Rz(yaw) Ry(pitch) Rx(roll)) in radians.
Eigen::Vector3d RollPitchYaw(const Eigen::Quaterniond& rotation);

}  // namespace visual_loop
}  // namespace fusemap

#endif  // FUSEMAP_VISUAL_LOOP_PLANAR_CONSTRAINT_H_
