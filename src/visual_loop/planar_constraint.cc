#include "fusemap/visual_loop/planar_constraint.h"

#include <algorithm>
#include <cmath>

#include "fusemap/common/math.h"

namespace fusemap {
namespace visual_loop {

bool PlanarConstraintOptions::IsValid(std::string* error) const {
  if (!(max_roll_pitch_rad > 0.0) || !(max_height_m > 0.0)) {
    *error = "planar constraint: max_roll_pitch_rad and max_height_m must be positive";
    return false;
  }
  return true;
}

Eigen::Vector3d RollPitchYaw(const Eigen::Quaterniond& rotation) {
  const Eigen::Matrix3d R = rotation.toRotationMatrix();
  const double pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  const double roll = std::atan2(R(2, 1), R(2, 2));
  const double yaw = std::atan2(R(1, 0), R(0, 0));
  return {roll, pitch, yaw};
}

common::Rigid3d BaseToBase(const common::Rigid3d& T_camera_a_camera_b,
                           const common::Rigid3d& T_base_camera_a,
                           const common::Rigid3d& T_base_camera_b) {
  return T_base_camera_a * T_camera_a_camera_b * T_base_camera_b.inverse();
}

PlanarConstraint ToPlanarConstraint(const common::Rigid3d& T_camera_a_camera_b,
                                    const Matrix6d& covariance_camera,
                                    const common::Rigid3d& T_base_camera_a,
                                    const common::Rigid3d& T_base_camera_b,
                                    const PlanarConstraintOptions& options) {
  PlanarConstraint result;
  const common::Rigid3d T_a_b = BaseToBase(T_camera_a_camera_b, T_base_camera_a, T_base_camera_b);
  const Eigen::Vector3d rpy = RollPitchYaw(T_a_b.rotation());
  result.roll_rad = rpy[0];
  result.pitch_rad = rpy[1];
  result.height_m = T_a_b.translation().z();
  result.T_base_a_base_b = common::Rigid2d(T_a_b.translation().x(), T_a_b.translation().y(), rpy[2]);

  // First-order propagation through the (smooth) map from the camera perturbation to
  // (x, y, yaw); numeric so it cannot drift from PerturbRight's convention.
  const auto planar = [&](const Eigen::Matrix<double, 6, 1>& delta) {
    const common::Rigid3d T = BaseToBase(PerturbRight(T_camera_a_camera_b, delta), T_base_camera_a,
                                         T_base_camera_b);
    return Eigen::Vector3d(T.translation().x(), T.translation().y(), RollPitchYaw(T.rotation())[2]);
  };
  constexpr double kStep = 1e-6;
  Eigen::Matrix<double, 3, 6> J;
  for (int k = 0; k < 6; ++k) {
    Eigen::Matrix<double, 6, 1> delta = Eigen::Matrix<double, 6, 1>::Zero();
    delta[k] = kStep;
    Eigen::Vector3d d = planar(delta) - planar(-delta);
    d[2] = common::NormalizeAngle(d[2]);
    J.col(k) = d / (2.0 * kStep);
  }
  result.covariance = J * covariance_camera * J.transpose();

  if (std::abs(result.roll_rad) > options.max_roll_pitch_rad ||
      std::abs(result.pitch_rad) > options.max_roll_pitch_rad) {
    result.reason = "roll " + std::to_string(result.roll_rad) + " rad / pitch " +
                    std::to_string(result.pitch_rad) + " rad off the floor plane";
    return result;
  }
  if (std::abs(result.height_m) > options.max_height_m) {
    result.reason = "height change " + std::to_string(result.height_m) + " m off the floor plane";
    return result;
  }
  result.accepted = true;
  return result;
}

}  // namespace visual_loop
}  // namespace fusemap
