#include "fusemap/mapping/pose_extrapolator_2d.h"

#include <gtest/gtest.h>

namespace fusemap {
namespace mapping {
namespace {

using common::Rigid2d;

sensor::OdometryData Odom(double t, double x, double y, double a) {
  sensor::OdometryData o;
  o.stamp_s = t;
  o.pose = Rigid2d(x, y, a);
  return o;
}

TEST(PoseExtrapolator2DTest, AppliesInterpolatedOdometryIncrementInTheRobotFrame) {
  PoseExtrapolator2D extrapolator;
  // Odometry frame rotated against the map: only the increment may matter.
  ASSERT_TRUE(extrapolator.AddOdometry(Odom(0.0, 5.0, 5.0, 1.0)));
  ASSERT_TRUE(extrapolator.AddOdometry(Odom(1.0, 5.0 + std::cos(1.0), 5.0 + std::sin(1.0), 1.0)));
  extrapolator.AddPose(0.0, Rigid2d(0.0, 0.0, common::kPi / 2));
  // Half way between odometry samples the robot moved 0.5 m forward, i.e. +y in the map.
  const Rigid2d predicted = extrapolator.ExtrapolatePose(0.5);
  EXPECT_NEAR(predicted.x(), 0.0, 1e-9);
  EXPECT_NEAR(predicted.y(), 0.5, 1e-9);
  EXPECT_NEAR(predicted.angle_rad(), common::kPi / 2, 1e-9);
}

// A looping log player restarts the odometry where the log began, 60 m from where it ended:
// that jump is no motion. After ForgetMotion the next scan is predicted at the last pose, and
// odometry counts again from the first sample after it.
TEST(PoseExtrapolator2DTest, MotionAcrossATimeResetIsNotTakenFromOdometry) {
  PoseExtrapolator2D extrapolator;
  ASSERT_TRUE(extrapolator.AddOdometry(Odom(0.0, 60.0, 0.0, 0.0)));
  extrapolator.AddPose(0.0, Rigid2d(10.0, 0.0, 0.0));
  ASSERT_TRUE(extrapolator.AddOdometry(Odom(0.1, 60.1, 0.0, 0.0)));
  extrapolator.AddPose(0.1, Rigid2d(10.1, 0.0, 0.0));
  extrapolator.ForgetMotion();
  ASSERT_TRUE(extrapolator.AddOdometry(Odom(1.1, 0.0, 0.0, 0.0)));
  Rigid2d predicted = extrapolator.ExtrapolatePose(1.15);
  EXPECT_NEAR(predicted.x(), 10.1, 1e-9);  // not 10.1 - 60.1, nor moved on at 1 m/s
  EXPECT_NEAR(predicted.y(), 0.0, 1e-9);
  extrapolator.AddPose(1.15, Rigid2d(10.1, 0.0, 0.0));
  ASSERT_TRUE(extrapolator.AddOdometry(Odom(1.2, 0.0, 0.2, 0.0)));
  ASSERT_TRUE(extrapolator.AddOdometry(Odom(1.25, 0.0, 0.3, 0.0)));
  predicted = extrapolator.ExtrapolatePose(1.25);
  EXPECT_NEAR(predicted.x(), 10.1, 1e-9);
  EXPECT_NEAR(predicted.y(), 0.2, 1e-9);  // from the odometry at 1.15 (0.1) to 1.25 (0.3)
}

TEST(PoseExtrapolator2DTest, ConstantVelocityWithoutOdometry) {
  PoseExtrapolator2D extrapolator;
  extrapolator.AddPose(0.0, Rigid2d(0.0, 0.0, 0.0));
  extrapolator.AddPose(0.1, Rigid2d(0.1, 0.0, 0.01));
  const Rigid2d predicted = extrapolator.ExtrapolatePose(0.3);
  EXPECT_NEAR(predicted.x(), 0.3, 1e-9);
  EXPECT_NEAR(predicted.angle_rad(), 0.03, 1e-9);
}

TEST(PoseExtrapolator2DTest, ImuYawRateOverridesEstimatedRotation) {
  PoseExtrapolator2D extrapolator;
  extrapolator.AddPose(0.0, Rigid2d(0.0, 0.0, 0.0));
  extrapolator.AddPose(0.1, Rigid2d(0.0, 0.0, 0.0));
  sensor::ImuData imu;
  imu.stamp_s = 0.1;
  imu.angular_velocity_radps.z() = 0.5;
  ASSERT_TRUE(extrapolator.AddImu(imu));
  EXPECT_NEAR(extrapolator.ExtrapolatePose(0.3).angle_rad(), 0.1, 1e-9);
}

TEST(PoseExtrapolator2DTest, RejectsOutOfOrderOdometry) {
  PoseExtrapolator2D extrapolator;
  ASSERT_TRUE(extrapolator.AddOdometry(Odom(1.0, 0, 0, 0)));
  EXPECT_FALSE(extrapolator.AddOdometry(Odom(0.5, 0, 0, 0)));
  Rigid2d pose;
  EXPECT_FALSE(extrapolator.InterpolateOdometry(0.5, &pose));
}

TEST(PoseExtrapolator2DTest, StaleOdometryHoldsTheRobotStillInsteadOfGuessingVelocity) {
  PoseExtrapolator2D extrapolator;
  ASSERT_TRUE(extrapolator.AddOdometry(Odom(0.0, 0.0, 0.0, 0.0)));
  ASSERT_TRUE(extrapolator.AddOdometry(Odom(0.2, 0.2, 0.0, 0.0)));
  extrapolator.AddPose(0.2, Rigid2d(1.0, 0.0, 0.0));
  // 0.1 s after the last sample: the 1 m/s odometry velocity is extrapolated.
  EXPECT_NEAR(extrapolator.ExtrapolatePose(0.3).x(), 1.1, 1e-9);
  // 3 s after it: odometry stopped reporting, so no motion is assumed.
  EXPECT_NEAR(extrapolator.ExtrapolatePose(3.2).x(), 1.0, 1e-9);
}

TEST(PoseExtrapolator2DTest, PastTimesReturnTheLastPose) {
  PoseExtrapolator2D extrapolator;
  extrapolator.AddPose(2.0, Rigid2d(1.0, 2.0, 0.3));
  const Rigid2d p = extrapolator.ExtrapolatePose(1.0);
  EXPECT_NEAR(p.x(), 1.0, 1e-12);
  EXPECT_NEAR(p.angle_rad(), 0.3, 1e-12);
}

}  // namespace
}  // namespace mapping
}  // namespace fusemap
