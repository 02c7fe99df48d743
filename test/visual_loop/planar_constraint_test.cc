#include "fusemap/visual_loop/planar_constraint.h"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "visual_loop/synthetic_views.h"

namespace fusemap {
namespace visual_loop {
namespace {

common::Rigid3d CameraMount() { return testing::CameraMount(0.5, 5.0 * M_PI / 180.0); }

common::Rigid3d CameraMotionFor(const common::Rigid3d& T_base_a_base_b) {
  const common::Rigid3d mount = CameraMount();
  return mount.inverse() * T_base_a_base_b * mount;
}

TEST(PlanarConstraintTest, APlanarMotionComesBackThroughTheMount) {
  const common::Rigid2d truth(1.2, -0.4, 0.6);
  const common::Rigid3d T_camera_a_camera_b = CameraMotionFor(common::Rigid3d::FromRigid2d(truth));
  Matrix6d covariance = Matrix6d::Identity() * 1e-6;
  const PlanarConstraint result = ToPlanarConstraint(T_camera_a_camera_b, covariance, CameraMount(),
                                                     CameraMount(), PlanarConstraintOptions{});
  ASSERT_TRUE(result.accepted) << result.reason;
  EXPECT_NEAR(result.T_base_a_base_b.x(), 1.2, 1e-9);
  EXPECT_NEAR(result.T_base_a_base_b.y(), -0.4, 1e-9);
  EXPECT_NEAR(result.T_base_a_base_b.angle_rad(), 0.6, 1e-9);
  EXPECT_NEAR(result.roll_rad, 0.0, 1e-9);
  EXPECT_NEAR(result.height_m, 0.0, 1e-9);
  // An isotropic camera covariance stays positive definite and of the same order.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(result.covariance);
  EXPECT_GT(eigen.eigenvalues().minCoeff(), 1e-8);
  EXPECT_LT(eigen.eigenvalues().maxCoeff(), 1e-4);
}

TEST(PlanarConstraintTest, CovarianceFollowsTheCameraAxes) {
  // Uncertainty only along the optical axis (camera z) of camera b = base x at zero yaw.
  const common::Rigid3d T_camera_a_camera_b = CameraMotionFor(common::Rigid3d::Identity());
  Matrix6d covariance = Matrix6d::Zero();
  covariance(2, 2) = 0.01;
  const PlanarConstraint result = ToPlanarConstraint(T_camera_a_camera_b, covariance, CameraMount(),
                                                     CameraMount(), PlanarConstraintOptions{});
  ASSERT_TRUE(result.accepted) << result.reason;
  const double cos_tilt = std::cos(5.0 * M_PI / 180.0);
  EXPECT_NEAR(result.covariance(0, 0), 0.01 * cos_tilt * cos_tilt, 1e-8);
  EXPECT_NEAR(result.covariance(1, 1), 0.0, 1e-8);
  EXPECT_NEAR(result.covariance(2, 2), 0.0, 1e-8);
}

TEST(PlanarConstraintTest, ARolledOrLiftedTransformIsRejectedWithAReason) {
  const common::Rigid3d rolled = testing::PoseFromTranslationRpy(1.0, 0.0, 0.0, 0.2, 0.0, 0.3);
  const PlanarConstraint roll = ToPlanarConstraint(CameraMotionFor(rolled), Matrix6d::Identity(),
                                                   CameraMount(), CameraMount(), PlanarConstraintOptions{});
  EXPECT_FALSE(roll.accepted);
  EXPECT_NEAR(roll.roll_rad, 0.2, 1e-9);
  EXPECT_NE(roll.reason.find("roll"), std::string::npos) << roll.reason;

  const common::Rigid3d pitched = testing::PoseFromTranslationRpy(1.0, 0.0, 0.0, 0.0, -0.1, 0.0);
  EXPECT_FALSE(ToPlanarConstraint(CameraMotionFor(pitched), Matrix6d::Identity(), CameraMount(),
                                  CameraMount(), PlanarConstraintOptions{})
                   .accepted);

  const common::Rigid3d lifted = testing::PoseFromTranslationRpy(1.0, 0.0, 0.3, 0.0, 0.0, 0.0);
  const PlanarConstraint lift = ToPlanarConstraint(CameraMotionFor(lifted), Matrix6d::Identity(),
                                                   CameraMount(), CameraMount(), PlanarConstraintOptions{});
  EXPECT_FALSE(lift.accepted);
  EXPECT_NE(lift.reason.find("height"), std::string::npos) << lift.reason;
}

}  // namespace
}  // namespace visual_loop
}  // namespace fusemap
