#include "fusemap/mapping/local_trajectory_builder_2d.h"

#include <gtest/gtest.h>

#include <algorithm>
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
  // Within half a 0.05 m cell: Ceres (occupied_space_weight 10) settles on the interpolated
  // grid's peak, which a submap of one scan places up to that far from the points.
  EXPECT_LT((still->T_local_tracking.translation() - first->T_local_tracking.translation()).norm(),
            0.025);
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

// Along the same arc, steps alternating 0.2 m and 1.2 m (4.6 and 27.5 deg) 0.1 s apart: the
// constant-velocity prediction is off by ~1 m and ~23 deg on every scan after the second.
common::Rigid2d JumpyPose(int i) {
  const double s_m = 0.7 * (i / 2 * 2) + (i % 2 == 1 ? 0.2 : 0.0);
  return test_world::ArcPose(1, s_m);
}

LocalTrajectoryBuilderOptions2D NoOdometryOptions(bool initial_match) {
  LocalTrajectoryBuilderOptions2D options = TestOptions();
  options.use_odometry = false;
  options.pose_queue_duration_s = 0.15;
  options.submaps.resolution_m = 0.1;
  options.initial_branch_and_bound_match.enabled = initial_match;
  // 1 deg beams leave gaps on far walls at 0.05 m; 0.2 m cells close them.
  options.initial_branch_and_bound_match.matching_resolution_m = 0.2;
  options.initial_branch_and_bound_match.fast_correlative_scan_matcher.linear_search_window_m = 2.0;
  options.initial_branch_and_bound_match.fast_correlative_scan_matcher.angular_search_window_rad =
      common::DegToRad(45.0);
  // On every scan (the no-odometry setting, as in config/orebro.yaml), unknown cells at 0.1.
  options.initial_branch_and_bound_match.only_at_window_edge = false;
  options.initial_branch_and_bound_match.fast_correlative_scan_matcher.branch_and_bound_depth = 5;
  options.initial_branch_and_bound_match.fast_correlative_scan_matcher.min_score = 0.5;
  options.initial_branch_and_bound_match.fast_correlative_scan_matcher
      .translation_delta_cost_weight = 0.0;
  options.initial_branch_and_bound_match.unknown_probability = kMinProbability;
  options.initial_branch_and_bound_match.unknown_padding_m = 10.0;
  return options;
}

struct TrackingError {
  double max_m = 0.0;
  double max_rad = 0.0;
};

// Runs `num_scans` of JumpyPose through `builder`; errors relative to the first pose.
TrackingError TrackJumpyPath(LocalTrajectoryBuilder2D* builder, int num_scans,
                             std::vector<common::Rigid2d>* estimates) {
  const std::vector<Segment> walls = Room();
  TrackingError error;
  for (int i = 0; i < num_scans; ++i) {
    const auto result = builder->AddScan(SimulateScan(walls, JumpyPose(i), 0.1 * i));
    if (!result.has_value()) {
      ADD_FAILURE() << "scan " << i;
      return error;
    }
    estimates->push_back(result->T_local_tracking);
    const common::Rigid2d truth = JumpyPose(0).inverse() * JumpyPose(i);
    const common::Rigid2d estimate = estimates->front().inverse() * estimates->back();
    error.max_m = std::max(error.max_m, (truth.translation() - estimate.translation()).norm());
    error.max_rad = std::max(error.max_rad, AngleError(truth, estimate));
  }
  return error;
}

TEST(LocalTrajectoryBuilder2DTest, InitialBranchAndBoundMatchTracksLargeJumpsWithoutOdometry) {
  constexpr int kNumScans = 20;  // 13.3 m, most of a lap around the island
  std::vector<common::Rigid2d> with_estimates;
  LocalTrajectoryBuilder2D with(NoOdometryOptions(true));
  const TrackingError with_error = TrackJumpyPath(&with, kNumScans, &with_estimates);
  std::vector<common::Rigid2d> without_estimates;
  LocalTrajectoryBuilder2D without(NoOdometryOptions(false));
  const TrackingError without_error = TrackJumpyPath(&without, kNumScans, &without_estimates);
  std::printf("jumpy path max error: with %.4f m %.3f deg, without %.3f m %.2f deg\n",
              with_error.max_m, with_error.max_rad * 180.0 / common::kPi, without_error.max_m,
              without_error.max_rad * 180.0 / common::kPi);
  // Within about a 0.1 m submap cell: far walls seen by 1 deg beams are sparse at this size.
  EXPECT_LT(with_error.max_m, 0.2);
  EXPECT_LT(with_error.max_rad, common::DegToRad(2.0));
  EXPECT_EQ(with.stats().initial_match_rejected, 0);
  EXPECT_EQ(with.stats().inserted, kNumScans);
  // The small real-time window alone cannot follow these jumps.
  EXPECT_GT(without_error.max_m, 0.5);
  EXPECT_EQ(without.stats().initial_match_rejected, 0);
}

// Tracks `num_scans` of the jumpy path with `options` and again with the wide search disabled,
// expects the same poses bit for bit, and returns the first run's counters.
LocalTrajectoryBuilder2D::Stats ExpectPosesAsWithoutWideSearch(
    LocalTrajectoryBuilderOptions2D options, int num_scans) {
  LocalTrajectoryBuilder2D widened(options);
  options.initial_branch_and_bound_match.enabled = false;
  LocalTrajectoryBuilder2D plain(options);
  std::vector<common::Rigid2d> widened_estimates, plain_estimates;
  TrackJumpyPath(&widened, num_scans, &widened_estimates);
  TrackJumpyPath(&plain, num_scans, &plain_estimates);
  EXPECT_EQ(widened_estimates.size(), plain_estimates.size());
  for (size_t i = 0; i < std::min(widened_estimates.size(), plain_estimates.size()); ++i) {
    EXPECT_EQ(widened_estimates[i].translation(), plain_estimates[i].translation()) << i;
    EXPECT_EQ(widened_estimates[i].angle_rad(), plain_estimates[i].angle_rad()) << i;
  }
  return widened.stats();
}

TEST(LocalTrajectoryBuilder2DTest, InitialMatchBelowMinScoreKeepsPredictionAndCounts) {
  constexpr int kNumScans = 6;
  LocalTrajectoryBuilderOptions2D options = NoOdometryOptions(true);
  // No candidate's mean probability exceeds 1.
  options.initial_branch_and_bound_match.fast_correlative_scan_matcher.min_score = 1.0;
  // Rejected everywhere, the stage leaves the poses bit for bit as if it were disabled.
  const LocalTrajectoryBuilder2D::Stats stats = ExpectPosesAsWithoutWideSearch(options, kNumScans);
  // Every scan but the first (which has no submap to match against) is counted.
  EXPECT_EQ(stats.initial_match_rejected, kNumScans - 1);
}

// only_at_window_edge: the wide search runs only where the small window's answer is on its
// border, and follows the same jumps as running it on every scan.
TEST(LocalTrajectoryBuilder2DTest, WideSearchAtWindowEdgeTracksLargeJumps) {
  constexpr int kNumScans = 20;
  LocalTrajectoryBuilderOptions2D options = NoOdometryOptions(true);
  options.initial_branch_and_bound_match.only_at_window_edge = true;
  LocalTrajectoryBuilder2D builder(options);
  std::vector<common::Rigid2d> estimates;
  const TrackingError error = TrackJumpyPath(&builder, kNumScans, &estimates);
  std::printf("jumpy path max error at window edge: %.4f m %.3f deg, %d edge matches, %d taken\n",
              error.max_m, error.max_rad * 180.0 / common::kPi,
              builder.stats().window_edge_matches, builder.stats().wide_matches_taken);
  // Within three 0.1 m cells: the real-time match started from the wide answer decides.
  EXPECT_LT(error.max_m, 0.3);
  EXPECT_LT(error.max_rad, common::DegToRad(2.0));
  EXPECT_GT(builder.stats().wide_matches_taken, 0);
  EXPECT_LE(builder.stats().wide_matches_taken, builder.stats().window_edge_matches);
  EXPECT_EQ(builder.stats().inserted, kNumScans);
}

// A path the small window follows by itself: the wide search's answer is never taken (it may
// run where a scan's best offset is a cell at the window's border), and the poses are bit for
// bit those without the stage.
TEST(LocalTrajectoryBuilder2DTest, WideSearchAtWindowEdgeLeavesSmoothPathAlone) {
  LocalTrajectoryBuilderOptions2D options = TestOptions();
  options.initial_branch_and_bound_match.enabled = true;
  options.initial_branch_and_bound_match.only_at_window_edge = true;
  LocalTrajectoryBuilder2D widened(options);
  LocalTrajectoryBuilder2D plain(TestOptions());
  const std::vector<Segment> walls = Room();
  for (int i = 0; i < 15; ++i) {
    const common::Rigid2d truth = test_world::ArcPose(1, 0.05 * i);
    const auto a = widened.AddScan(SimulateScan(walls, truth, 0.1 * i));
    const auto b = plain.AddScan(SimulateScan(walls, truth, 0.1 * i));
    ASSERT_TRUE(a.has_value() && b.has_value()) << i;
    EXPECT_EQ(a->T_local_tracking.translation(), b->T_local_tracking.translation()) << i;
    EXPECT_EQ(a->T_local_tracking.angle_rad(), b->T_local_tracking.angle_rad()) << i;
  }
  EXPECT_EQ(widened.stats().wide_matches_taken, 0);
}

// A wide answer that fits no better than never-observed space is not taken: with the real-time
// matcher reading such space as 0.9 (above any mean a scan here reaches), the wide search runs
// at the window's edge but every pose is the one without it.
TEST(LocalTrajectoryBuilder2DTest, WideAnswerFittingNoBetterThanUnknownSpaceIsNotTaken) {
  LocalTrajectoryBuilderOptions2D options = NoOdometryOptions(true);
  options.initial_branch_and_bound_match.only_at_window_edge = true;
  options.real_time_correlative_scan_matcher.unknown_probability = kMaxProbability;
  const LocalTrajectoryBuilder2D::Stats stats = ExpectPosesAsWithoutWideSearch(options, 10);
  EXPECT_GT(stats.window_edge_matches, 0);
  EXPECT_EQ(stats.wide_matches_taken, 0);
}

// With Ceres alone (no real-time window, as in sim.yaml) only_at_window_edge never searches
// wide: the poses are those without the stage, not those of a search on every scan.
TEST(LocalTrajectoryBuilder2DTest, WideSearchAtWindowEdgeNeedsTheRealTimeMatcher) {
  LocalTrajectoryBuilderOptions2D options = NoOdometryOptions(true);
  options.use_online_correlative_scan_matching = false;
  options.initial_branch_and_bound_match.only_at_window_edge = true;
  EXPECT_EQ(ExpectPosesAsWithoutWideSearch(options, 6).window_edge_matches, 0);
}

// Issue 18, item 3: one odometry message at x = 1e300 early in a run hung local SLAM in the
// grid's growth loop. The absurd prediction is now replaced by the last pose, and tracking
// carries on from the following odometry.
TEST(LocalTrajectoryBuilder2DTest, AbsurdOdometryPoseIsIgnored) {
  const std::vector<Segment> walls = Room();
  LocalTrajectoryBuilder2D builder(TestOptions());
  constexpr int kNumScans = 30;
  constexpr int kAbsurdScan = 4;
  for (int i = 0; i < kNumScans; ++i) {
    const double stamp_s = 0.1 * i;
    // Just before scan kAbsurdScan the only new odometry is the corrupt one.
    if (i == kAbsurdScan) {
      builder.AddOdometry({stamp_s - 0.05, common::Rigid2d(1e300, -1e300, 0.0)});
    } else {
      builder.AddOdometry({stamp_s, TruePose(i)});
    }
    const auto result = builder.AddScan(SimulateScan(walls, TruePose(i), stamp_s));
    ASSERT_TRUE(result.has_value()) << "scan " << i;
    // The local frame starts at the first scan's pose.
    const common::Rigid2d expected = TruePose(0).inverse() * TruePose(i);
    const double error_m = (result->T_local_tracking.translation() - expected.translation()).norm();
    // Matched from the last pose (one 0.1 m step behind), then tracking as before.
    EXPECT_LT(error_m, i < kAbsurdScan + 2 ? 0.2 : 0.05) << "scan " << i;
  }
  EXPECT_GE(builder.stats().absurd_predictions, 1);
  EXPECT_EQ(builder.stats().insertions_refused, 0);
  EXPECT_EQ(builder.stats().inserted, kNumScans);
}

}  // namespace
}  // namespace mapping
}  // namespace fusemap
