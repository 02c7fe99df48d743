#ifndef FUSEMAP_POSE_GRAPH_SE2_COST_FUNCTION_H_
#define FUSEMAP_POSE_GRAPH_SE2_COST_FUNCTION_H_

#include <Eigen/Core>

#include "fusemap/common/rigid_transform.h"

namespace ceres {
class CostFunction;
}

namespace fusemap {
namespace pose_graph {

// The one SE(2) edge residual used by both the sparse pose adjustment and the generic g2o graph:
// over parameter blocks {x, y, theta} of T_map_from and T_map_to,
//   e = [R(z_theta)^T (t_hat - t_z); NormalizeAngle(theta_hat - theta_z)],
//   T_hat = T_map_from^-1 * T_map_to,  residual = sqrt_information * e,
// i.e. g2o's EdgeSE2 error log(Z^-1 * T_hat) (Kuemmerle et al. 2011). With isotropic translation
// weights its norm equals Cartographer's SPA residual (Hess et al. 2016, Eqs. (SPA), (4), (5)).
// The caller takes ownership (normally a ceres::Problem).
ceres::CostFunction* CreateSe2EdgeCostFunction(const common::Rigid2d& T_from_to,
                                               const Eigen::Matrix3d& sqrt_information);

// Upper-triangular S with S^T S = information (Cholesky), so that |S e|^2 = e^T information e.
// Returns false if `information` is not symmetric positive definite.
bool SqrtInformation(const Eigen::Matrix3d& information, Eigen::Matrix3d* sqrt_information);

// The diagonal information of Cartographer-style weights: residual = weights .* e.
Eigen::Matrix3d InformationFromWeights(double translation_weight, double rotation_weight);
// The same, but with (almost) no information along one mode of the error: a translation along
// `unmeasured_direction` (a unit vector in the measurement's frame; zero: none unmeasured) with
// `turn_rad_per_m` of rotation per metre of it (a match that slides round a curved wall). A
// 1e-6 fraction of it is kept so that the information stays positive definite for
// SqrtInformation.
Eigen::Matrix3d InformationWithoutMode(double translation_weight, double rotation_weight,
                                       const Eigen::Vector2d& unmeasured_direction,
                                       double turn_rad_per_m);
// The same with `weight_fraction` of translation_weight along `weak_direction` (a unit vector in
// the measurement's frame; zero: full weight every way), in (0, 1].
Eigen::Matrix3d InformationFromWeights(double translation_weight, double rotation_weight,
                                       const Eigen::Vector2d& weak_direction,
                                       double weight_fraction);
// `information` with `weight_fraction` of its weight (its square root) left along `mode`, an
// error vector [x, y, angle] (not zero), and unchanged on what is orthogonal to it in the
// information's metric: e^T result e = f^2 e^T information e for e along mode.
Eigen::Matrix3d WeakenMode(const Eigen::Matrix3d& information, const Eigen::Vector3d& mode,
                           double weight_fraction);

// The unwhitened error e above, for reporting and tests.
Eigen::Vector3d Se2EdgeError(const common::Rigid2d& T_map_from, const common::Rigid2d& T_map_to,
                             const common::Rigid2d& T_from_to);

}  // namespace pose_graph
}  // namespace fusemap

#endif  // FUSEMAP_POSE_GRAPH_SE2_COST_FUNCTION_H_
