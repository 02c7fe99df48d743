#include "fusemap/eval/relative_pose_error.h"

#include <gtest/gtest.h>

#include <cmath>

#include "fusemap/common/math.h"

namespace fusemap {
namespace eval {
namespace {

// Straight line along x at 1 m/s, 10 Hz, 20 s.
Trajectory StraightGt() {
  Trajectory t;
  for (int i = 0; i <= 200; ++i) {
    t.push_back(TimedPose3d{0.1 * i, common::Rigid3d(Eigen::Vector3d(0.1 * i, 0.0, 0.0),
                                                     Eigen::Quaterniond::Identity())});
  }
  return t;
}

TEST(RpeTest, IdenticalTrajectoriesHaveZeroError) {
  const Trajectory gt = StraightGt();
  const RpeResult r = ComputeRpe(gt, gt, RpeOptions());
  EXPECT_EQ(r.trans_m.count, 191);  // Pairs (i, i+10) for i = 0..190.
  EXPECT_NEAR(r.trans_m.rmse, 0.0, 1e-12);
  EXPECT_NEAR(r.rot_deg.mean, 0.0, 1e-9);
}

TEST(RpeTest, ScaleDriftPerMetreIsRecovered) {
  // Odometry that over-reports distance by 2 %: per metre of true travel, 0.02 m error.
  const Trajectory gt = StraightGt();
  Trajectory est = gt;
  for (TimedPose3d& p : est) {
    p.pose = common::Rigid3d(1.02 * p.pose.translation(), p.pose.rotation());
  }
  RpeOptions options;
  options.delta = 2.0;
  const RpeResult r = ComputeRpe(gt, est, options);
  EXPECT_NEAR(r.trans_m.rmse, 0.04, 1e-9);
  EXPECT_NEAR(r.trans_m.mean, 0.04, 1e-9);
}

TEST(RpeTest, HeadingDriftPerSecondIsRecovered) {
  // The estimate turns at 1 deg/s while the truth goes straight: over delta = 1 s the
  // rotational error is 1 deg everywhere (the translational one depends on the arc).
  const Trajectory gt = StraightGt();
  Trajectory est;
  common::Rigid3d pose;
  est.push_back(TimedPose3d{0.0, pose});
  const common::Rigid3d step(
      Eigen::Vector3d(0.1, 0.0, 0.0),
      Eigen::Quaterniond(Eigen::AngleAxisd(common::DegToRad(0.1), Eigen::Vector3d::UnitZ())));
  for (int i = 1; i <= 200; ++i) {
    pose = pose * step;
    est.push_back(TimedPose3d{0.1 * i, pose});
  }
  RpeOptions options;
  options.delta_unit = DeltaUnit::kSeconds;
  const RpeResult r = ComputeRpe(gt, est, options);
  EXPECT_EQ(r.rot_deg.count, 191);
  EXPECT_NEAR(r.rot_deg.mean, 1.0, 1e-6);
  EXPECT_NEAR(r.rot_deg.max, 1.0, 1e-6);
  // Sum of 10 steps of 0.1 m turned by 0..0.9 deg: the chord misses the true 1 m by a
  // fixed, small amount.
  EXPECT_GT(r.trans_m.mean, 0.0);
  EXPECT_LT(r.trans_m.mean, 0.01);
  EXPECT_NEAR(r.trans_m.std, 0.0, 1e-9);
}

TEST(RpeTest, DeltaLongerThanTrajectoryGivesNoPairs) {
  const Trajectory gt = StraightGt();
  RpeOptions options;
  options.delta = 50.0;
  EXPECT_EQ(ComputeRpe(gt, gt, options).trans_m.count, 0);
}

TEST(RpeTest, ParseOptionsAndBadUnit) {
  std::string error;
  auto reader = common::ConfigReader::FromString("delta: 0.5\ndelta_unit: s\n", "test", &error);
  ASSERT_NE(reader, nullptr) << error;
  const RpeOptions options = ParseRpeOptions(*reader);
  EXPECT_TRUE(reader->Finish(&error)) << error;
  EXPECT_DOUBLE_EQ(options.delta, 0.5);
  EXPECT_EQ(options.delta_unit, DeltaUnit::kSeconds);

  auto bad = common::ConfigReader::FromString("delta_unit: furlong\n", "test", &error);
  ASSERT_NE(bad, nullptr) << error;
  ParseRpeOptions(*bad);
  EXPECT_FALSE(bad->Finish(&error));
  EXPECT_NE(error.find("delta_unit"), std::string::npos);

  auto negative = common::ConfigReader::FromString("delta_unit: m\ndelta: -1\n", "test", &error);
  ASSERT_NE(negative, nullptr) << error;
  ParseRpeOptions(*negative);
  EXPECT_FALSE(negative->Finish(&error));
  EXPECT_EQ(error, "test:2: key 'delta': must be finite and > 0");
}

}  // namespace
}  // namespace eval
}  // namespace fusemap
