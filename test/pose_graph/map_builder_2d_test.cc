#include "fusemap/pose_graph/map_builder_2d.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <functional>
#include <limits>
#include <random>
#include <vector>

#include "fusemap/common/math.h"
#include "testing/room_map_builder_options.h"
#include "testing/synthetic_room.h"

namespace fusemap {
namespace pose_graph {
namespace {

using test_world::kArcRadiusM;
using test_world::Room;
using test_world::Segment;
using test_world::SimulateScan;

constexpr double kStepM = 0.15;

common::Rigid2d TruePose(int i) { return test_world::ArcPose(i, kStepM); }

MapBuilderOptions2D TestOptions(int optimize_every_n_nodes) {
  MapBuilderOptions2D options = test_world::RoomMapBuilderOptions();
  options.global_slam.optimize_every_n_nodes = optimize_every_n_nodes;
  return options;
}

// Every submap sees most of the small room, so each new one covers its predecessors again.
OverlappingSubmapsTrimmerOptions2D Trimmer() {
  OverlappingSubmapsTrimmerOptions2D trimmer;
  trimmer.fresh_submaps_count = 1;
  trimmer.min_covered_area_m2 = 0.5;
  trimmer.min_added_submaps_count = 2;
  return trimmer;
}

struct LoopRun {
  PoseGraph2D::Stats stats;
  double end_error_m = 0.0;
  int moved_callbacks = 0;
  int moved_submaps = 0;
};

// `turns` around the island (1.1: the end revisits the start); odometry with 2 % scale error
// and 0.3 deg yaw bias per step, ranges with +-2 cm noise.
LoopRun DriveLoop(int optimize_every_n_nodes, common::Executor* executor, double turns = 1.1,
                  const OverlappingSubmapsTrimmerOptions2D& trimmer = {}) {
  const std::vector<Segment> walls = Room();
  MapBuilderOptions2D options = TestOptions(optimize_every_n_nodes);
  options.global_slam.overlapping_submaps_trimmer = trimmer;
  std::string error;
  EXPECT_TRUE(options.IsValid(&error)) << error;
  MapBuilder2D builder(options, executor);
  LoopRun run;
  builder.pose_graph().AddSubmapsMovedCallback([&run](const std::vector<SubmapMove>& moves) {
    ++run.moved_callbacks;
    run.moved_submaps += static_cast<int>(moves.size());
  });
  std::mt19937 rng(42);
  const int num_scans = static_cast<int>(turns * 2.0 * common::kPi * kArcRadiusM / kStepM);
  common::Rigid2d odom = TruePose(0);
  for (int i = 0; i < num_scans; ++i) {
    if (i > 0) {
      const common::Rigid2d delta = TruePose(i - 1).inverse() * TruePose(i);
      odom = odom * common::Rigid2d(1.02 * delta.translation(),
                                    delta.angle_rad() + common::DegToRad(0.3));
    }
    const double stamp_s = 0.1 * i;
    builder.AddOdometry({stamp_s, odom});
    const auto result = builder.AddScan(SimulateScan(walls, TruePose(i), stamp_s, 0.02, &rng));
    EXPECT_TRUE(result);
    // Every scan binds to a submap the pose graph knows, the one local SLAM matches against.
    if (!result || result->submap_id < 0) {
      ADD_FAILURE() << "scan " << i << " has no submap";
      continue;
    }
    EXPECT_EQ(builder.pose_graph().submaps().at(result->submap_id)->T_local_submap().translation(),
              result->T_local_submap.translation());
  }
  builder.Finish();
  run.stats = builder.pose_graph().stats();
  const auto poses = builder.NodePoses();
  EXPECT_EQ(static_cast<int>(poses.size()), builder.local_slam().stats().inserted);
  // Nodes are every scan here (each step turns more than the motion filter's 1 deg).
  EXPECT_EQ(static_cast<int>(poses.size()), num_scans);
  const common::Rigid2d truth = TruePose(0).inverse() * TruePose(num_scans - 1);
  const common::Rigid2d estimate = poses.front().pose.inverse() * poses.back().pose;
  run.end_error_m = (truth.translation() - estimate.translation()).norm();
  return run;
}

TEST(MapBuilder2DTest, LoopClosureBeatsLocalSlamAlone) {
  common::InlineExecutor executor;
  const LoopRun local_only = DriveLoop(0, &executor);
  const LoopRun global = DriveLoop(10, &executor);
  std::printf("end error: local only %.4f m, with loop closure %.4f m (%d closures in %d "
              "searches, %d optimisations)\n",
              local_only.end_error_m, global.end_error_m, global.stats.loop_closures_found,
              global.stats.loop_closure_searches, global.stats.optimizations);
  EXPECT_EQ(local_only.stats.loop_closure_searches, 0);
  EXPECT_EQ(local_only.moved_callbacks, 0);
  EXPECT_GT(global.stats.loop_closures_found, 0);
  EXPECT_GT(global.moved_callbacks, 0);
  EXPECT_GT(global.moved_submaps, 0);
  EXPECT_GT(local_only.end_error_m, 0.2);
  EXPECT_LT(global.end_error_m, 0.5 * local_only.end_error_m);
  EXPECT_LT(global.end_error_m, 0.08);
}

TEST(MapBuilder2DTest, TrimmerKeepsTheGraphSmallOverRepeatedLaps) {
  common::InlineExecutor executor;
  const LoopRun kept = DriveLoop(10, &executor, 2.1);
  const LoopRun trimmed = DriveLoop(10, &executor, 2.1, Trimmer());
  const int live_submaps = trimmed.stats.submaps - trimmed.stats.trimmed_submaps;
  std::printf("2.1 laps: %d submaps and %d constraints kept, %d submaps (%d trimmed, %d nodes "
              "trimmed) and %d constraints with the trimmer; end error %.4f m vs %.4f m\n",
              kept.stats.submaps, kept.stats.constraints, trimmed.stats.submaps,
              trimmed.stats.trimmed_submaps, trimmed.stats.trimmed_nodes,
              trimmed.stats.constraints, trimmed.end_error_m, kept.end_error_m);
  EXPECT_EQ(kept.stats.trimmed_submaps, 0);
  EXPECT_EQ(kept.stats.trimmed_nodes, 0);
  EXPECT_GT(trimmed.stats.trimmed_nodes, 0);
  EXPECT_EQ(trimmed.stats.submaps, kept.stats.submaps);
  // About one lap's worth: a cell stays with the newest submap that knows it well, and the
  // far side of the island is known well only by the submaps made there (10 of 22 held; 7
  // when a single miss counted as knowing a cell).
  EXPECT_LE(live_submaps, kept.stats.submaps / 2);
  EXPECT_LT(trimmed.stats.constraints, kept.stats.constraints / 2);
  // Trimmed nodes keep their last pose, so the whole trajectory is still there and right.
  EXPECT_LT(trimmed.end_error_m, 0.08);
}

// A pool that falls behind, as one does when a log plays faster than the CPU can search: it
// runs `RunOne` tasks, first come first served, only when the test gives it time (a fixed
// number per scan), so searches pile up.
class BackloggedExecutor : public common::Executor {
 public:
  void Schedule(std::function<void()> task) override {
    tasks_.push_back(std::move(task));
    max_backlog_ = std::max(max_backlog_, tasks_.size());
  }
  void ScheduleFirst(std::function<void()> task) override {
    tasks_.push_front(std::move(task));
    max_backlog_ = std::max(max_backlog_, tasks_.size());
  }
  void WaitIdle() override {
    while (!tasks_.empty()) RunOne();
  }
  void RunOne() {
    if (tasks_.empty()) return;
    std::function<void()> task = std::move(tasks_.front());
    tasks_.pop_front();
    task();
  }
  size_t max_backlog() const { return max_backlog_; }

 private:
  std::deque<std::function<void()>> tasks_;
  size_t max_backlog_ = 0;
};

// The most submaps held at once over `turns` laps with the trimmer on; odometry exact, or with
// DriveLoop's errors. `after_scan` runs after every scan.
int MaxHeldSubmaps(common::Executor* executor, double turns, bool exact_odometry = true,
                   const std::function<void()>& after_scan = [] {}) {
  const std::vector<Segment> walls = Room();
  MapBuilderOptions2D options = TestOptions(10);
  options.global_slam.overlapping_submaps_trimmer = Trimmer();
  MapBuilder2D builder(options, executor);
  std::mt19937 rng(42);
  const int num_scans = static_cast<int>(turns * 2.0 * common::kPi * kArcRadiusM / kStepM);
  int max_held = 0;
  common::Rigid2d odom = TruePose(0);
  for (int i = 0; i < num_scans; ++i) {
    if (i > 0) {
      const common::Rigid2d delta = TruePose(i - 1).inverse() * TruePose(i);
      odom = exact_odometry ? TruePose(i)
                            : odom * common::Rigid2d(1.02 * delta.translation(),
                                                     delta.angle_rad() + common::DegToRad(0.3));
    }
    const double stamp_s = 0.1 * i;
    builder.AddOdometry({stamp_s, odom});
    EXPECT_TRUE(builder.AddScan(SimulateScan(walls, TruePose(i), stamp_s, 0.02, &rng)));
    after_scan();
    const PoseGraph2D::Stats stats = builder.pose_graph().stats();
    max_held = std::max(max_held, stats.submaps - stats.trimmed_submaps);
  }
  builder.Finish();
  return max_held;
}

TEST(MapBuilder2DTest, TrimmingKeepsUpBehindABacklogOfSearches) {
  // Regression: compaction and the optimisation (which trims) queued behind the searches, so
  // with a backlog the trimmer ran rarely and the submaps held grew lap after lap (intel played
  // six times: 87 held instead of ~45, RSS rising 118 -> 250 MB).
  common::InlineExecutor inline_executor;
  BackloggedExecutor backlogged;
  const int inline_held = MaxHeldSubmaps(&inline_executor, 4.1);
  const int backlogged_held =
      MaxHeldSubmaps(&backlogged, 4.1, true, [&backlogged] { backlogged.RunOne(); });
  std::printf("4.1 laps: at most %d submaps held inline, %d behind a backlog of up to %zu tasks\n",
              inline_held, backlogged_held, backlogged.max_backlog());
  // Searches did pile up (inline, none ever wait).
  EXPECT_GT(backlogged.max_backlog(), 50u);
  // One optimisation's worth of lag at most.
  EXPECT_LE(backlogged_held, inline_held + 2);
}

TEST(MapBuilder2DTest, TrimmingKeepsUpBehindABacklogWithDriftingOdometry) {
  // Regression: with odometry that drifts, a submap is only trimmed once loop closures have tied
  // the new submaps over it to the old ones. First come, first served, those searches waited
  // behind thousands for nodes long past (and the precomputation of new submaps behind them),
  // the estimate drifted out of the search window, and 32 submaps were held against 11 inline.
  // Newest node first, precomputation ahead: 12. (Precomputation ahead alone: 21.)
  common::InlineExecutor inline_executor;
  BackloggedExecutor backlogged;
  const int inline_held = MaxHeldSubmaps(&inline_executor, 4.1, false);
  const int backlogged_held =
      MaxHeldSubmaps(&backlogged, 4.1, false, [&backlogged] { backlogged.RunOne(); });
  std::printf("4.1 laps, drifting odometry: at most %d submaps held inline, %d behind a backlog "
              "of up to %zu tasks\n",
              inline_held, backlogged_held, backlogged.max_backlog());
  EXPECT_GT(backlogged.max_backlog(), 50u);
  EXPECT_LE(backlogged_held, inline_held + 3);
}

TEST(MapBuilder2DTest, ThreadPoolRunFindsLoopClosures) {
  common::ThreadPool pool(2);
  const LoopRun run = DriveLoop(10, &pool);
  EXPECT_GT(run.stats.loop_closures_found, 0);
  EXPECT_GT(run.stats.optimizations, 0);
  EXPECT_LT(run.end_error_m, 0.08);
}

// Ground truth G(t) of a robot driving a curve.
common::Rigid2d G(double t) { return common::Rigid2d(t, 0.5 * t * t, 0.3 * t); }

TEST(DensifyWithOdometryTest, BlendsTheCorrectionsOfBothNeighbouringNodes) {
  // The odometry frame is off from the map frame by X; the node at t = 2 carries a correction C
  // (as after a loop closure), the node at t = 1 none. Between them the correction grows
  // linearly in time; outside them the nearest node's correction applies.
  const common::Rigid2d X(3.0, -1.0, 0.7);
  const Eigen::Vector2d c(0.2, 0.1);
  const common::Rigid2d C(c.x(), c.y(), 0.0);
  const std::vector<MapBuilder2D::TimedPose2d> nodes = {{1.0, G(1.0)}, {2.0, C * G(2.0)}};
  std::vector<sensor::OdometryData> odometry;
  for (const double t : {0.5, 1.0, 1.25, 1.5, 1.5, 2.0, 2.5}) odometry.push_back({t, X * G(t)});

  const auto dense = DensifyWithOdometry(nodes, odometry);
  ASSERT_EQ(dense.size(), 6u);  // the repeated stamp 1.5 is dropped
  const std::vector<double> stamps = {0.5, 1.0, 1.25, 1.5, 2.0, 2.5};
  for (size_t i = 0; i < dense.size(); ++i) {
    const double t = stamps[i];
    EXPECT_DOUBLE_EQ(dense[i].stamp_s, t);
    const double fraction = std::clamp(t - 1.0, 0.0, 1.0);
    const Eigen::Vector2d expected = G(t).translation() + fraction * c;
    EXPECT_NEAR(dense[i].pose.x(), expected.x(), 1e-9) << "t " << t;
    EXPECT_NEAR(dense[i].pose.y(), expected.y(), 1e-9) << "t " << t;
    EXPECT_NEAR(common::NormalizeAngle(dense[i].pose.angle_rad() - G(t).angle_rad()), 0.0, 1e-9)
        << "t " << t;
  }
}

// A looping log restarts its odometry at 1.5 s, 60 m away: a sample on either side of that
// break follows only the node on its own side, never the increment across the jump.
TEST(DensifyWithOdometryTest, TakesNoIncrementAcrossATimeReset) {
  const std::vector<MapBuilder2D::TimedPose2d> nodes = {{1.0, common::Rigid2d(5.0, 0.0, 0.0)},
                                                        {2.0, common::Rigid2d(5.5, 0.0, 0.0)}};
  std::vector<sensor::OdometryData> odometry = {{1.0, common::Rigid2d(60.0, 0.0, 0.0)},
                                                {1.25, common::Rigid2d(60.1, 0.0, 0.0)},
                                                {1.5, common::Rigid2d(0.0, 0.0, 0.0)},
                                                {2.0, common::Rigid2d(0.2, 0.0, 0.0)}};
  const auto dense = DensifyWithOdometry(nodes, odometry, {1.5});
  ASSERT_EQ(dense.size(), 4u);
  EXPECT_NEAR(dense[1].pose.x(), 5.1, 1e-9);  // after the node at 1 s, on the old odometry
  EXPECT_NEAR(dense[2].pose.x(), 5.3, 1e-9);  // before the node at 2 s, on the new odometry
  EXPECT_NEAR(dense[3].pose.x(), 5.5, 1e-9);
  // Without the break the blend mixes the two odometry frames: tens of metres off.
  EXPECT_GT(std::abs(DensifyWithOdometry(nodes, odometry)[2].pose.x() - 5.3), 10.0);
}

TEST(DensifyWithOdometryTest, PassesThroughNodesWithoutJumps) {
  // Rotational corrections on both nodes: the dense trajectory must meet each node at its stamp
  // and move smoothly in between (composing onto the nearest node alone jumped at t = 1.5).
  const common::Rigid2d X(-2.0, 4.0, -1.1);
  const std::vector<MapBuilder2D::TimedPose2d> nodes = {
      {1.0, common::Rigid2d(0.1, -0.2, 0.05) * G(1.0)},
      {2.0, common::Rigid2d(-0.3, 0.2, -0.08) * G(2.0)}};
  std::vector<sensor::OdometryData> odometry;
  for (int k = 0; k <= 100; ++k) {
    const double t = 1.0 + 0.01 * k;
    odometry.push_back({t, X * G(t)});
  }
  const auto dense = DensifyWithOdometry(nodes, odometry);
  ASSERT_EQ(dense.size(), odometry.size());
  for (const size_t i : {size_t{0}, dense.size() - 1}) {
    const auto& node = nodes[i == 0 ? 0 : 1];
    EXPECT_NEAR((dense[i].pose.translation() - node.pose.translation()).norm(), 0.0, 1e-9);
    EXPECT_NEAR(common::NormalizeAngle(dense[i].pose.angle_rad() - node.pose.angle_rad()), 0.0,
                1e-9);
  }
  // Ground truth moves at most |dG/dt| * 0.01 s <= 0.03 m per step here; the blended
  // correction adds at most |0.4, 0.4| * 0.01 plus the rotation's lever arm.
  double max_step_m = 0.0;
  for (size_t i = 1; i < dense.size(); ++i) {
    max_step_m = std::max(
        max_step_m, (dense[i].pose.translation() - dense[i - 1].pose.translation()).norm());
  }
  EXPECT_LT(max_step_m, 0.05);
}

TEST(DensifyWithOdometryTest, NodeBetweenOdometrySamplesIsInterpolated) {
  // Straight-line motion, where interpolating odometry is exact.
  const auto line = [](double t) { return common::Rigid2d(2.0 * t, 0.0, 0.0); };
  const std::vector<MapBuilder2D::TimedPose2d> nodes = {{1.05, line(1.05)}};
  const std::vector<sensor::OdometryData> odometry = {{1.0, line(1.0)}, {1.1, line(1.1)},
                                                      {1.2, line(1.2)}};
  const auto dense = DensifyWithOdometry(nodes, odometry);
  ASSERT_EQ(dense.size(), 3u);
  for (size_t i = 0; i < dense.size(); ++i) {
    EXPECT_NEAR(dense[i].pose.x(), odometry[i].pose.x(), 1e-9);
    EXPECT_NEAR(dense[i].pose.y(), 0.0, 1e-12);
  }
}

TEST(DensifyWithOdometryTest, WithoutOdometryReturnsNodes) {
  const std::vector<MapBuilder2D::TimedPose2d> nodes = {{1.0, G(1.0)}, {2.0, G(2.0)}};
  const auto dense = DensifyWithOdometry(nodes, {});
  ASSERT_EQ(dense.size(), 2u);
  EXPECT_DOUBLE_EQ(dense[1].stamp_s, 2.0);
  EXPECT_DOUBLE_EQ(dense[1].pose.y(), G(2.0).y());
}

}  // namespace
}  // namespace pose_graph
}  // namespace fusemap
