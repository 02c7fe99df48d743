#include "fusemap/cloud/pose_interpolator.h"

#include <gtest/gtest.h>

#include <cmath>

#include "fusemap/common/math.h"

namespace fusemap {
namespace cloud {
namespace {

using Status = PoseInterpolator::Status;
constexpr double kTol = 1e-9;

TEST(PoseInterpolatorTest, InterpolatesLinearlyBetweenBracketingPoses) {
  PoseInterpolator interpolator{PoseInterpolatorOptions()};
  ASSERT_TRUE(interpolator.AddPose(10.0, common::Rigid2d(0.0, 0.0, 0.0)));
  ASSERT_TRUE(interpolator.AddPose(10.2, common::Rigid2d(1.0, -2.0, 0.4)));
  ASSERT_TRUE(interpolator.AddPose(10.4, common::Rigid2d(5.0, 5.0, 0.0)));
  const auto mid = interpolator.Lookup(10.05, 10.05);
  ASSERT_EQ(mid.status, Status::kReady);
  EXPECT_NEAR(mid.T_local_tracking.x(), 0.25, kTol);
  EXPECT_NEAR(mid.T_local_tracking.y(), -0.5, kTol);
  EXPECT_NEAR(mid.T_local_tracking.angle_rad(), 0.1, kTol);
  // Exactly on a sample, and on the last sample.
  const auto on = interpolator.Lookup(10.2, 10.2);
  ASSERT_EQ(on.status, Status::kReady);
  EXPECT_NEAR(on.T_local_tracking.x(), 1.0, kTol);
  EXPECT_EQ(interpolator.Lookup(10.4, 10.4).status, Status::kReady);
  // Second interval, not the nearest sample.
  const auto late = interpolator.Lookup(10.35, 10.35);
  ASSERT_EQ(late.status, Status::kReady);
  EXPECT_NEAR(late.T_local_tracking.x(), 4.0, kTol);
  EXPECT_NEAR(late.T_local_tracking.y(), 3.25, kTol);
  EXPECT_NEAR(late.T_local_tracking.angle_rad(), 0.1, kTol);
}

TEST(PoseInterpolatorTest, YawTakesTheShortArcAcrossPi) {
  PoseInterpolator interpolator{PoseInterpolatorOptions()};
  const double a = common::kPi - 0.1;
  interpolator.AddPose(1.0, common::Rigid2d(0.0, 0.0, a));
  interpolator.AddPose(1.1, common::Rigid2d(0.0, 0.0, -a));  // 0.2 rad further, across +pi.
  const auto mid = interpolator.Lookup(1.05, 1.05);
  ASSERT_EQ(mid.status, Status::kReady);
  EXPECT_NEAR(std::abs(mid.T_local_tracking.angle_rad()), common::kPi, 1e-9);
  const auto quarter = interpolator.Lookup(1.025, 1.025);
  ASSERT_EQ(quarter.status, Status::kReady);
  EXPECT_NEAR(quarter.T_local_tracking.angle_rad(), a + 0.05, 1e-9);
  const auto three_quarters = interpolator.Lookup(1.075, 1.075);
  EXPECT_NEAR(three_quarters.T_local_tracking.angle_rad(), -a - 0.05, 1e-9);
}

TEST(PoseInterpolatorTest, WaitsForALaterPoseThenDrops) {
  PoseInterpolatorOptions options;
  options.hold_s = 0.5;
  PoseInterpolator interpolator(options);
  EXPECT_EQ(interpolator.Lookup(1.0, 1.0).status, Status::kWait);  // No poses yet.
  interpolator.AddPose(0.9, common::Rigid2d(0.0, 0.0, 0.0));
  EXPECT_EQ(interpolator.Lookup(1.0, 1.2).status, Status::kWait);
  EXPECT_EQ(interpolator.Lookup(1.0, 1.5).status, Status::kWait);
  EXPECT_EQ(interpolator.num_dropped_timeout(), 0);
  EXPECT_EQ(interpolator.Lookup(1.0, 1.51).status, Status::kDrop);
  EXPECT_EQ(interpolator.num_dropped_timeout(), 1);
  // The pose arrives in time: the same frame becomes ready.
  interpolator.AddPose(1.1, common::Rigid2d(1.0, 0.0, 0.0));
  const auto ready = interpolator.Lookup(1.0, 1.2);
  ASSERT_EQ(ready.status, Status::kReady);
  EXPECT_NEAR(ready.T_local_tracking.x(), 0.5, kTol);
}

TEST(PoseInterpolatorTest, DropsAcrossLargeGapsAndBeforeHistory) {
  PoseInterpolatorOptions options;
  options.max_gap_s = 0.5;
  PoseInterpolator interpolator(options);
  interpolator.AddPose(1.0, common::Rigid2d(0.0, 0.0, 0.0));
  interpolator.AddPose(1.5, common::Rigid2d(1.0, 0.0, 0.0));
  interpolator.AddPose(2.1, common::Rigid2d(2.0, 0.0, 0.0));  // 0.6 s gap.
  EXPECT_EQ(interpolator.Lookup(1.25, 3.0).status, Status::kReady);  // Gap exactly max_gap_s.
  EXPECT_EQ(interpolator.Lookup(1.8, 3.0).status, Status::kDrop);
  EXPECT_EQ(interpolator.num_dropped_gap(), 1);
  EXPECT_EQ(interpolator.Lookup(0.99, 3.0).status, Status::kDrop);
  EXPECT_EQ(interpolator.num_dropped_too_old(), 1);
}

TEST(PoseInterpolatorTest, RejectsOutOfOrderAndDuplicateStamps) {
  PoseInterpolator interpolator{PoseInterpolatorOptions()};
  EXPECT_TRUE(interpolator.AddPose(2.0, common::Rigid2d(0.0, 0.0, 0.0)));
  EXPECT_FALSE(interpolator.AddPose(2.0, common::Rigid2d(9.0, 0.0, 0.0)));
  EXPECT_FALSE(interpolator.AddPose(1.0, common::Rigid2d(9.0, 0.0, 0.0)));
  EXPECT_FALSE(interpolator.AddPose(std::nan(""), common::Rigid2d(9.0, 0.0, 0.0)));
  EXPECT_EQ(interpolator.num_rejected_poses(), 3);
  EXPECT_EQ(interpolator.size(), 1u);
  EXPECT_NEAR(interpolator.Lookup(2.0, 2.0).T_local_tracking.x(), 0.0, kTol);
}

TEST(PoseInterpolatorTest, TrimsHistory) {
  PoseInterpolatorOptions options;
  options.max_history_s = 1.0;
  PoseInterpolator interpolator(options);
  for (int i = 0; i <= 50; ++i) interpolator.AddPose(0.1 * i, common::Rigid2d(0.1 * i, 0.0, 0.0));
  // Newest 5.0 s: keeps stamps >= 4.0 s, i.e. 4.0 .. 5.0 (11 samples; allow float rounding).
  EXPECT_GE(interpolator.size(), 10u);
  EXPECT_LE(interpolator.size(), 11u);
  EXPECT_GE(interpolator.oldest_stamp_s(), 4.0 - 1e-9);
  EXPECT_DOUBLE_EQ(interpolator.newest_stamp_s(), 5.0);
  EXPECT_EQ(interpolator.Lookup(3.5, 5.0).status, Status::kDrop);
  EXPECT_EQ(interpolator.Lookup(4.55, 5.0).status, Status::kReady);
}

TEST(PoseInterpolatorTest, OptionsValidationAndParsing) {
  std::string error;
  PoseInterpolatorOptions options;
  EXPECT_TRUE(options.IsValid(&error));
  options.max_gap_s = 0.0;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("max_gap_s"), std::string::npos);
  auto reader = common::ConfigReader::FromString("hold_s: 0.25\nmax_history_s: 10\n", "t", &error);
  ASSERT_NE(reader, nullptr);
  const PoseInterpolatorOptions parsed = ParsePoseInterpolatorOptions(*reader);
  EXPECT_TRUE(reader->Finish(&error)) << error;
  EXPECT_DOUBLE_EQ(parsed.hold_s, 0.25);
  EXPECT_DOUBLE_EQ(parsed.max_history_s, 10.0);
}

}  // namespace
}  // namespace cloud
}  // namespace fusemap
