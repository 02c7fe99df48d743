#include "fusemap/mapping/local_trajectory_builder_2d.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "fusemap/common/math.h"
#include "testing/synthetic_room.h"

namespace fusemap {
namespace mapping {
namespace {

using test_world::Room;
using test_world::Segment;
using test_world::SimulateScan;

// Counter-clockwise arc of radius 2.5 m around the island: 0.1 m and ~2.3 deg per step.
common::Rigid2d TruePose(int i) { return test_world::ArcPose(i, 0.1); }

LocalTrajectoryBuilderOptions2D TestOptions() {
  LocalTrajectoryBuilderOptions2D options;
  options.use_imu = false;
  options.submaps.num_range_data = 35;
  return options;
}

double AngleError(const common::Rigid2d& a, const common::Rigid2d& b) {
  return std::abs(common::NormalizeAngle(a.angle_rad() - b.angle_rad()));
}

TEST(LocalTrajectoryBuilder2DTest, TracksDriftingOdometryAccurately) {
  const std::vector<Segment> walls = Room();
  LocalTrajectoryBuilder2D builder(TestOptions());
  constexpr int kNumScans = 60;
  // Odometry with a 2 % scale error on translation and a 0.2 deg yaw bias per step.
  common::Rigid2d odom = TruePose(0);
  std::vector<common::Rigid2d> estimates;
  std::vector<common::Rigid2d> odometry;
  for (int i = 0; i < kNumScans; ++i) {
    if (i > 0) {
      const common::Rigid2d delta = TruePose(i - 1).inverse() * TruePose(i);
      odom = odom * common::Rigid2d(1.02 * delta.translation(),
                                    delta.angle_rad() + common::DegToRad(0.2));
    }
    const double stamp_s = 0.1 * i;
    builder.AddOdometry({stamp_s, odom});
    odometry.push_back(odom);
    const auto result = builder.AddScan(SimulateScan(walls, TruePose(i), stamp_s));
    ASSERT_TRUE(result.has_value()) << "scan " << i;
    estimates.push_back(result->T_local_tracking);
  }
  EXPECT_EQ(builder.stats().scans, kNumScans);
  EXPECT_EQ(builder.stats().inserted, kNumScans);  // every step exceeds the 1 deg filter

  double max_error_m = 0.0;
  double max_error_rad = 0.0;
  for (int i = 0; i < kNumScans; ++i) {
    const common::Rigid2d truth = TruePose(0).inverse() * TruePose(i);
    const common::Rigid2d estimate = estimates.front().inverse() * estimates[i];
    max_error_m = std::max(max_error_m, (truth.translation() - estimate.translation()).norm());
    max_error_rad = std::max(max_error_rad, AngleError(truth, estimate));
  }
  const common::Rigid2d truth_end = TruePose(0).inverse() * TruePose(kNumScans - 1);
  const common::Rigid2d odom_end = odometry.front().inverse() * odometry.back();
  const double odom_error_m = (truth_end.translation() - odom_end.translation()).norm();
  std::printf("local SLAM max error %.4f m %.4f deg; odometry end error %.3f m %.2f deg\n",
              max_error_m, max_error_rad * 180.0 / common::kPi, odom_error_m,
              AngleError(truth_end, odom_end) * 180.0 / common::kPi);
  EXPECT_LT(max_error_m, 0.05);
  EXPECT_LT(max_error_rad, common::DegToRad(1.0));
  // The drift is real: odometry alone is off by decimetres and degrees.
  EXPECT_GT(odom_error_m, 0.3);
  EXPECT_GT(AngleError(truth_end, odom_end), common::DegToRad(10.0));
}

TEST(LocalTrajectoryBuilder2DTest, SkipsScansWithTooFewReturnsAndOutOfOrderScans) {
  const std::vector<Segment> walls = Room();
  LocalTrajectoryBuilder2D builder(TestOptions());
  builder.AddOdometry({0.0, TruePose(0)});
  ASSERT_TRUE(builder.AddScan(SimulateScan(walls, TruePose(0), 0.0)).has_value());

  // Only 5 beams see anything (fewer than min_num_returns = 10).
  sensor::LaserScan sparse = SimulateScan(walls, TruePose(0), 0.1);
  for (size_t i = 5; i < sparse.ranges_m.size(); ++i) {
    sparse.ranges_m[i] = std::numeric_limits<float>::infinity();
  }
  EXPECT_FALSE(builder.AddScan(sparse).has_value());
  EXPECT_EQ(builder.stats().too_few_returns, 1);

  // Same stamp as the accepted scan, then an older one.
  EXPECT_FALSE(builder.AddScan(SimulateScan(walls, TruePose(0), 0.0)).has_value());
  EXPECT_FALSE(builder.AddScan(SimulateScan(walls, TruePose(0), -0.05)).has_value());
  EXPECT_EQ(builder.stats().out_of_order, 2);

  // The skipped sparse scan did not advance the clock: a good scan at its stamp is accepted.
  EXPECT_TRUE(builder.AddScan(SimulateScan(walls, TruePose(0), 0.1)).has_value());
  EXPECT_EQ(builder.stats().scans, 5);
  EXPECT_EQ(builder.stats().too_few_returns, 1);
  EXPECT_EQ(builder.stats().out_of_order, 2);
}

TEST(LocalTrajectoryBuilder2DTest, MotionFilterDropsStandingStillScan) {
  const std::vector<Segment> walls = Room();
  LocalTrajectoryBuilder2D builder(TestOptions());
  builder.AddOdometry({0.0, TruePose(0)});
  const auto first = builder.AddScan(SimulateScan(walls, TruePose(0), 0.0));
  ASSERT_TRUE(first.has_value());
  EXPECT_TRUE(first->insertion.has_value());
  ASSERT_EQ(first->insertion->insertion_submaps.size(), 1u);
  EXPECT_FALSE(first->insertion->filtered_cloud.empty());

  builder.AddOdometry({0.1, TruePose(0)});
  const auto still = builder.AddScan(SimulateScan(walls, TruePose(0), 0.1));
  ASSERT_TRUE(still.has_value());
  EXPECT_FALSE(still->insertion.has_value());
  EXPECT_LT((still->T_local_tracking.translation() - first->T_local_tracking.translation()).norm(),
            0.01);
  EXPECT_EQ(builder.stats().inserted, 1);

  // Moving 0.3 m (beyond max_distance_m = 0.2) is inserted again.
  const common::Rigid2d moved = TruePose(0) * common::Rigid2d(0.3, 0.0, 0.0);
  builder.AddOdometry({0.2, moved});
  const auto third = builder.AddScan(SimulateScan(walls, moved, 0.2));
  ASSERT_TRUE(third.has_value());
  EXPECT_TRUE(third->insertion.has_value());
  EXPECT_EQ(builder.stats().inserted, 2);
  EXPECT_NEAR(third->T_local_tracking.x() - first->T_local_tracking.x(), 0.3, 0.03);
}

}  // namespace
}  // namespace mapping
}  // namespace fusemap
