#include "fusemap/visual_loop/pose_covariance.h"

#include <cassert>

#include <Eigen/Dense>

namespace fusemap {
namespace visual_loop {

common::Rigid3d PerturbRight(const common::Rigid3d& T, const Eigen::Matrix<double, 6, 1>& delta) {
  const Eigen::Vector3d r = delta.tail<3>();
  const double angle = r.norm();
  const Eigen::Quaterniond rotation =
      angle > 0.0 ? Eigen::Quaterniond(Eigen::AngleAxisd(angle, r / angle))
                  : Eigen::Quaterniond::Identity();
  return T * common::Rigid3d(delta.head<3>(), rotation);
}

Eigen::Vector2d Project(const sensor::PinholeIntrinsics& intrinsics, const Eigen::Vector3d& p) {
  return {intrinsics.fx * p.x() / p.z() + intrinsics.cx, intrinsics.fy * p.y() / p.z() + intrinsics.cy};
}

double MeanReprojectionPx(const common::Rigid3d& T_b_a,
                          const std::vector<Eigen::Vector3d>& points_a,
                          const std::vector<Eigen::Vector2d>& pixels_b,
                          const sensor::PinholeIntrinsics& intrinsics_b) {
  assert(points_a.size() == pixels_b.size() && !points_a.empty());
  double error_sum = 0.0;
  for (size_t i = 0; i < points_a.size(); ++i) {
    error_sum += (Project(intrinsics_b, T_b_a * points_a[i]) - pixels_b[i]).norm();
  }
  return error_sum / static_cast<double>(points_a.size());
}

Matrix6d PnpCovariance(const common::Rigid3d& T_a_b, const std::vector<Eigen::Vector3d>& points_a,
                       const std::vector<Eigen::Vector2d>& pixels_b,
                       const sensor::PinholeIntrinsics& intrinsics_b) {
  assert(points_a.size() == pixels_b.size() && points_a.size() >= 4);
  const int n = static_cast<int>(points_a.size());
  const auto residuals = [&](const common::Rigid3d& T) {
    const common::Rigid3d T_b_a = T.inverse();
    Eigen::VectorXd r(2 * n);
    for (int i = 0; i < n; ++i) r.segment<2>(2 * i) = Project(intrinsics_b, T_b_a * points_a[i]) - pixels_b[i];
    return r;
  };
  const Eigen::VectorXd r0 = residuals(T_a_b);
  // Central differences: the projection is smooth and cheap, and this keeps the Jacobian
  // honest about the parameterisation PerturbRight defines.
  constexpr double kStep = 1e-6;
  Eigen::MatrixXd J(2 * n, 6);
  for (int k = 0; k < 6; ++k) {
    Eigen::Matrix<double, 6, 1> delta = Eigen::Matrix<double, 6, 1>::Zero();
    delta[k] = kStep;
    J.col(k) = (residuals(PerturbRight(T_a_b, delta)) - residuals(PerturbRight(T_a_b, -delta))) /
               (2.0 * kStep);
  }
  const double dof = std::max(1, 2 * n - 6);
  const double sigma_sq = std::max(r0.squaredNorm() / dof, 1e-4);  // a floor: never overconfident
  const Matrix6d information = J.transpose() * J;
  return sigma_sq * information.ldlt().solve(Matrix6d::Identity());
}

}  // namespace visual_loop
}  // namespace fusemap
