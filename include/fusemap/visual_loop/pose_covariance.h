#ifndef FUSEMAP_VISUAL_LOOP_POSE_COVARIANCE_H_
#define FUSEMAP_VISUAL_LOOP_POSE_COVARIANCE_H_

#include <vector>

#include <Eigen/Core>

#include "fusemap/common/rigid_transform.h"
#include "fusemap/sensor/rgbd_frame.h"

namespace fusemap {
namespace visual_loop {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

// Applies a small perturbation delta = (dx, dy, dz, rx, ry, rz) on the right:
// T * (translation d, rotation by the rotation vector r), both in T's child frame.
common::Rigid3d PerturbRight(const common::Rigid3d& T, const Eigen::Matrix<double, 6, 1>& delta);

// Covariance of T_a_b estimated by PnP from points_a (3D, camera a) seen at pixels_b in camera
// b: sigma^2 (J^T J)^-1, J the Jacobian of the reprojection residuals with respect to a
// right perturbation of T_a_b (PerturbRight; translation first), sigma^2 the residual variance
// sum(r^2) / (2n - 6) (Hartley & Zisserman, Sec. 5.2). Needs at least 4 points.
Matrix6d PnpCovariance(const common::Rigid3d& T_a_b, const std::vector<Eigen::Vector3d>& points_a,
                       const std::vector<Eigen::Vector2d>& pixels_b,
                       const sensor::PinholeIntrinsics& intrinsics_b);

// Pixel of p_camera (z > 0) through the pinhole.
Eigen::Vector2d Project(const sensor::PinholeIntrinsics& intrinsics, const Eigen::Vector3d& p_camera);

// Mean distance in pixels between points_a carried into camera b by T_b_a and projected, and
// pixels_b (as many, at least one).
double MeanReprojectionPx(const common::Rigid3d& T_b_a,
                          const std::vector<Eigen::Vector3d>& points_a,
                          const std::vector<Eigen::Vector2d>& pixels_b,
                          const sensor::PinholeIntrinsics& intrinsics_b);

}  // namespace visual_loop
}  // namespace fusemap

#endif  // FUSEMAP_VISUAL_LOOP_POSE_COVARIANCE_H_
