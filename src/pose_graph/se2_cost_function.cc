#include "fusemap/pose_graph/se2_cost_function.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/ceres.h>

#include <Eigen/Cholesky>
#include <cmath>

#include "fusemap/common/math.h"

namespace fusemap {
namespace pose_graph {
namespace {

// Error of the measured relative pose z_from_to against the one implied by the two poses,
// expressed in the measurement's frame.
template <typename T>
void ComputeError(const T* const from, const T* const to, double z_x_m, double z_y_m,
                  double z_angle_rad, T* error) {
  using std::cos;
  using std::sin;
  const T cos_from = cos(from[2]);
  const T sin_from = sin(from[2]);
  const T dx = to[0] - from[0];
  const T dy = to[1] - from[1];
  // t_hat = R(theta_from)^T (t_to - t_from).
  const T hat_x = cos_from * dx + sin_from * dy;
  const T hat_y = -sin_from * dx + cos_from * dy;
  const double cos_z = std::cos(z_angle_rad);
  const double sin_z = std::sin(z_angle_rad);
  const T ex = hat_x - T(z_x_m);
  const T ey = hat_y - T(z_y_m);
  error[0] = cos_z * ex + sin_z * ey;
  error[1] = -sin_z * ex + cos_z * ey;
  error[2] = common::NormalizeAngle(to[2] - from[2] - T(z_angle_rad));
}

class Se2EdgeCostFunctor {
 public:
  static ceres::CostFunction* Create(const common::Rigid2d& T_from_to,
                                     const Eigen::Matrix3d& sqrt_information) {
    return new ceres::AutoDiffCostFunction<Se2EdgeCostFunctor, 3, 3, 3>(
        new Se2EdgeCostFunctor(T_from_to, sqrt_information));
  }

  template <typename T>
  bool operator()(const T* const T_map_from, const T* const T_map_to, T* residual) const {
    T error[3];
    ComputeError(T_map_from, T_map_to, p_from_to_m_.x(), p_from_to_m_.y(), yaw_from_to_rad_,
                 error);
    for (int r = 0; r < 3; ++r) {
      residual[r] = T(0.0);
      for (int c = 0; c < 3; ++c) residual[r] += sqrt_information_(r, c) * error[c];
    }
    return true;
  }

 private:
  Se2EdgeCostFunctor(const common::Rigid2d& T_from_to, const Eigen::Matrix3d& sqrt_information)
      : p_from_to_m_(T_from_to.translation()),
        yaw_from_to_rad_(T_from_to.angle_rad()),
        sqrt_information_(sqrt_information) {}

  const Eigen::Vector2d p_from_to_m_;
  const double yaw_from_to_rad_;
  const Eigen::Matrix3d sqrt_information_;
};

}  // namespace

ceres::CostFunction* CreateSe2EdgeCostFunction(const common::Rigid2d& T_from_to,
                                               const Eigen::Matrix3d& sqrt_information) {
  return Se2EdgeCostFunctor::Create(T_from_to, sqrt_information);
}

bool SqrtInformation(const Eigen::Matrix3d& information, Eigen::Matrix3d* sqrt_information) {
  if (!information.allFinite()) return false;
  if (!information.isApprox(information.transpose(), 1e-9)) return false;
  const Eigen::LLT<Eigen::Matrix3d> llt(information);
  if (llt.info() != Eigen::Success) return false;
  const Eigen::Matrix3d upper = llt.matrixU();
  if ((upper.diagonal().array() <= 0.0).any()) return false;
  *sqrt_information = upper;
  return true;
}

Eigen::Matrix3d InformationFromWeights(double translation_weight, double rotation_weight) {
  return Eigen::Vector3d(translation_weight * translation_weight,
                         translation_weight * translation_weight,
                         rotation_weight * rotation_weight)
      .asDiagonal();
}

namespace {

// The weights' information with weight_fraction of it along a translation of
// `direction` (zero: none weakened) turning turn_rad_per_m with it.
Eigen::Matrix3d WeakAlong(double translation_weight, double rotation_weight,
                          const Eigen::Vector2d& direction, double turn_rad_per_m,
                          double weight_fraction) {
  const Eigen::Matrix3d information = InformationFromWeights(translation_weight, rotation_weight);
  if (direction.isZero()) return information;
  const Eigen::Vector2d d = direction.normalized();
  return WeakenMode(information, Eigen::Vector3d(d.x(), d.y(), turn_rad_per_m), weight_fraction);
}

}  // namespace

Eigen::Matrix3d InformationWithoutMode(double translation_weight, double rotation_weight,
                                       const Eigen::Vector2d& unmeasured_direction,
                                       double turn_rad_per_m) {
  // 1e-6 of the information is 1e-3 of the weight.
  return WeakAlong(translation_weight, rotation_weight, unmeasured_direction, turn_rad_per_m,
                   1e-3);
}

Eigen::Matrix3d InformationFromWeights(double translation_weight, double rotation_weight,
                                       const Eigen::Vector2d& weak_direction,
                                       double weight_fraction) {
  return WeakAlong(translation_weight, rotation_weight, weak_direction, 0.0, weight_fraction);
}

Eigen::Matrix3d WeakenMode(const Eigen::Matrix3d& information, const Eigen::Vector3d& mode,
                           double weight_fraction) {
  const Eigen::Vector3d held = information * mode;
  const double along = mode.dot(held);
  if (!(along > 0.0)) return information;
  Eigen::Matrix3d result =
      information - (1.0 - weight_fraction * weight_fraction) / along * held * held.transpose();
  // Exactly symmetric for the Cholesky factorisation.
  return 0.5 * (result + result.transpose());
}

Eigen::Vector3d Se2EdgeError(const common::Rigid2d& T_map_from, const common::Rigid2d& T_map_to,
                             const common::Rigid2d& T_from_to) {
  const double from[3] = {T_map_from.x(), T_map_from.y(), T_map_from.angle_rad()};
  const double to[3] = {T_map_to.x(), T_map_to.y(), T_map_to.angle_rad()};
  double error[3];
  ComputeError(from, to, T_from_to.x(), T_from_to.y(), T_from_to.angle_rad(), error);
  return Eigen::Vector3d(error[0], error[1], error[2]);
}

}  // namespace pose_graph
}  // namespace fusemap
