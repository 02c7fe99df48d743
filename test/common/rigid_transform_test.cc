#include "fusemap/common/rigid_transform.h"

#include <gtest/gtest.h>

#include <random>

namespace fusemap {
namespace common {
namespace {

void ExpectNear(const Rigid2d& a, const Rigid2d& b, double tol) {
  EXPECT_NEAR(a.x(), b.x(), tol);
  EXPECT_NEAR(a.y(), b.y(), tol);
  EXPECT_NEAR(NormalizeAngle(a.angle_rad() - b.angle_rad()), 0.0, tol);
}

TEST(NormalizeAngleTest, WrapsIntoHalfOpenInterval) {
  EXPECT_NEAR(NormalizeAngle(kPi), -kPi, 1e-12);
  EXPECT_NEAR(NormalizeAngle(-kPi), -kPi, 1e-12);
  EXPECT_NEAR(NormalizeAngle(3 * kPi + 0.1), -kPi + 0.1, 1e-12);
  EXPECT_NEAR(NormalizeAngle(1e-5), 1e-5, 1e-15);
  EXPECT_NEAR(NormalizeAngle(-2 * kPi - 1e-5), -1e-5, 1e-12);
}

TEST(Rigid2dTest, IdentityLeavesPointsAlone) {
  const Eigen::Vector2d p(1.5, -2.0);
  EXPECT_TRUE((Rigid2d::Identity() * p).isApprox(p));
}

TEST(Rigid2dTest, ComposesFramesInOrder) {
  // Robot at (1, 0) facing +y; a point 1 m ahead of it is at (1, 1) in the map.
  const Rigid2d T_map_robot(1.0, 0.0, kPi / 2);
  const Eigen::Vector2d p_map = T_map_robot * Eigen::Vector2d(1.0, 0.0);
  EXPECT_NEAR(p_map.x(), 1.0, 1e-12);
  EXPECT_NEAR(p_map.y(), 1.0, 1e-12);
}

TEST(Rigid2dTest, InverseRoundTripsIncludingAtPlusMinusPi) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-10.0, 10.0);
  const double angles[] = {0.0, 1e-5, -1e-5, kPi, -kPi, kPi - 1e-9, 2.5};
  for (double a : angles) {
    const Rigid2d T(u(rng), u(rng), a);
    ExpectNear(T * T.inverse(), Rigid2d::Identity(), 1e-9);
    ExpectNear(T.inverse() * T, Rigid2d::Identity(), 1e-9);
    ExpectNear(T.inverse().inverse(), T, 1e-9);
  }
}

TEST(Rigid2dTest, CompositionIsAssociative) {
  const Rigid2d a(1, 2, 0.3), b(-0.5, 4, 3.0), c(0.1, -0.2, -2.9);
  ExpectNear((a * b) * c, a * (b * c), 1e-12);
}

TEST(Rigid2dTest, InterpolatesTheShortWayRoundPi) {
  const Rigid2d a(0, 0, kPi - 0.1), b(2, 0, -kPi + 0.1);
  const Rigid2d mid = Interpolate(a, b, 0.5);
  EXPECT_NEAR(mid.x(), 1.0, 1e-12);
  EXPECT_NEAR(std::abs(mid.angle_rad()), kPi, 1e-9);
}

TEST(Rigid3dTest, RoundTripsThroughRigid2d) {
  const Rigid2d planar(3.0, -1.0, -kPi + 1e-5);
  ExpectNear(Rigid3d::FromRigid2d(planar).ToRigid2d(), planar, 1e-9);
}

TEST(Rigid3dTest, InverseAndComposition) {
  const Rigid3d a(Eigen::Vector3d(1, 2, 3),
                  Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())));
  const Rigid3d id = a * a.inverse();
  EXPECT_LT(id.translation().norm(), 1e-12);
  EXPECT_NEAR(id.rotation().w(), 1.0, 1e-12);
  const Eigen::Vector3d p(0.5, -0.25, 2.0);
  EXPECT_TRUE((a.inverse() * (a * p)).isApprox(p, 1e-12));
}

TEST(Rigid3dTest, SlerpHalfway) {
  const Rigid3d a = Rigid3d::FromRigid2d(Rigid2d(0, 0, 0));
  const Rigid3d b = Rigid3d::FromRigid2d(Rigid2d(2, 4, 1.0));
  const Rigid2d mid = Interpolate(a, b, 0.5).ToRigid2d();
  ExpectNear(mid, Rigid2d(1, 2, 0.5), 1e-12);
}

}  // namespace
}  // namespace common
}  // namespace fusemap
