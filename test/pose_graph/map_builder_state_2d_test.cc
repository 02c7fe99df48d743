#include "fusemap/pose_graph/map_builder_state_2d.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <functional>
#include <memory>
#include <random>
#include <vector>

#include "fusemap/common/math.h"
#include "fusemap/pose_graph/map_builder_2d.h"
#include "testing/room_map_builder_options.h"
#include "testing/synthetic_room.h"

namespace fusemap {
namespace pose_graph {
namespace {

constexpr double kStepM = 0.15;

common::Rigid2d TruePose(int i) { return test_world::ArcPose(i, kStepM); }

MapBuilderOptions2D TestOptions(double sampling_ratio) {
  MapBuilderOptions2D options = test_world::RoomMapBuilderOptions();
  options.global_slam.optimize_every_n_nodes = 10;
  options.global_slam.constraint_builder.sampling_ratio = sampling_ratio;
  return options;
}

// The small room: each new submap covers the older ones again, so trimming goes on all the time.
MapBuilderOptions2D TrimmingOptions() {
  MapBuilderOptions2D options = TestOptions(0.3);
  OverlappingSubmapsTrimmerOptions2D& trimmer = options.global_slam.overlapping_submaps_trimmer;
  trimmer.fresh_submaps_count = 1;
  trimmer.min_covered_area_m2 = 0.5;
  trimmer.min_added_submaps_count = 2;
  return options;
}

struct Input {
  sensor::OdometryData odometry;
  sensor::LaserScan scan;
};

// `turns` around the island (1.1: the end revisits the start), biased odometry, noisy ranges.
std::vector<Input> LoopInput(double turns = 1.1) {
  const auto walls = test_world::Room();
  std::mt19937 rng(7);
  const int num_scans =
      static_cast<int>(turns * 2.0 * common::kPi * test_world::kArcRadiusM / kStepM);
  std::vector<Input> input;
  common::Rigid2d odom = TruePose(0);
  for (int i = 0; i < num_scans; ++i) {
    if (i > 0) {
      const common::Rigid2d delta = TruePose(i - 1).inverse() * TruePose(i);
      odom = odom * common::Rigid2d(1.02 * delta.translation(),
                                    delta.angle_rad() + common::DegToRad(0.3));
    }
    const double stamp_s = 0.1 * i;
    input.push_back({{stamp_s, odom},
                     test_world::SimulateScan(walls, TruePose(i), stamp_s, 0.02, &rng)});
  }
  return input;
}

void Feed(const std::vector<Input>& input, size_t begin, size_t end, MapBuilder2D* builder) {
  for (size_t i = begin; i < end; ++i) {
    builder->AddOdometry(input[i].odometry);
    builder->AddScan(input[i].scan);
  }
}

void ExpectSameSubmaps(const MapBuilderState2D& a, const MapBuilderState2D& b) {
  ASSERT_EQ(a.submaps.size(), b.submaps.size());
  for (size_t s = 0; s < a.submaps.size(); ++s) {
    const mapping::SubmapState2D& x = a.submaps[s];
    const mapping::SubmapState2D& y = b.submaps[s];
    EXPECT_EQ(x.limits.num_x_cells, y.limits.num_x_cells) << "submap " << s;
    EXPECT_EQ(x.limits.num_y_cells, y.limits.num_y_cells) << "submap " << s;
    EXPECT_EQ(x.limits.origin_m, y.limits.origin_m) << "submap " << s;
    EXPECT_EQ(x.cells, y.cells) << "submap " << s;
    EXPECT_EQ(x.num_range_data, y.num_range_data) << "submap " << s;
    EXPECT_EQ(x.finished, y.finished) << "submap " << s;
    EXPECT_EQ(x.T_local_submap.translation(), y.T_local_submap.translation()) << "submap " << s;
  }
  EXPECT_EQ(a.active_submaps, b.active_submaps);
}

// Restore is exact and the inline executor deterministic, so the runs agree to rounding.
void ExpectSamePoses(const std::vector<MapBuilder2D::TimedPose2d>& expected,
                     const std::vector<MapBuilder2D::TimedPose2d>& actual) {
  ASSERT_EQ(actual.size(), expected.size());
  for (size_t i = 0; i < actual.size(); ++i) {
    EXPECT_EQ(actual[i].stamp_s, expected[i].stamp_s);
    EXPECT_NEAR(actual[i].pose.x(), expected[i].pose.x(), 1e-9) << "node " << i;
    EXPECT_NEAR(actual[i].pose.y(), expected[i].pose.y(), 1e-9) << "node " << i;
    EXPECT_NEAR(common::NormalizeAngle(actual[i].pose.angle_rad() - expected[i].pose.angle_rad()),
                0.0, 1e-9)
        << "node " << i;
  }
}

TEST(MapBuilderState2DTest, RestoredBuilderContinuesExactlyLikeTheOriginal) {
  const std::vector<Input> input = LoopInput();
  const size_t split = input.size() / 2;
  common::InlineExecutor executor;
  // Sampling below 1, so the restored builder must also continue the samplers' sequences.
  const MapBuilderOptions2D options = TestOptions(0.3);
  MapBuilder2D original(options, &executor);
  Feed(input, 0, split, &original);
  const MapBuilderState2D state = original.ExportState();
  ASSERT_EQ(state.pose_graph.nodes.size(), split);
  ASSERT_GE(state.submaps.size(), 3u);
  ASSERT_EQ(state.active_submaps.size(), 2u);

  auto restored = MapBuilder2D::Restore(options, &executor, state);
  // The restored builder exports the same state: grids round-trip cell for cell.
  const MapBuilderState2D again = restored->ExportState();
  ExpectSameSubmaps(state, again);
  EXPECT_EQ(again.pose_graph.constraints.size(), state.pose_graph.constraints.size());
  EXPECT_EQ(again.pose_graph.stats.loop_closures_found, state.pose_graph.stats.loop_closures_found);

  Feed(input, split, input.size(), &original);
  Feed(input, split, input.size(), restored.get());
  // The end of the loop closes against submaps that only exist restored in `restored`.
  EXPECT_GT(restored->pose_graph().stats().loop_closures_found,
            state.pose_graph.stats.loop_closures_found);
  original.Finish();
  restored->Finish();
  ASSERT_EQ(restored->NodePoses().size(), input.size());
  ExpectSamePoses(original.NodePoses(), restored->NodePoses());
  ExpectSameSubmaps(original.ExportState(), restored->ExportState());
  EXPECT_EQ(original.pose_graph().stats().loop_closure_searches,
            restored->pose_graph().stats().loop_closure_searches);
}

// With the real-time matcher and its adaptive heading prior on (the default profile's local
// SLAM), the prior's window is state too: restored with it the run continues exactly; restored
// without it, the first scans are matched with the configured weight and the run departs.
TEST(MapBuilderState2DTest, AdaptiveHeadingPriorWindowIsRestored) {
  const std::vector<Input> input = LoopInput();
  const size_t split = input.size() / 2;
  common::InlineExecutor executor;
  MapBuilderOptions2D options = TestOptions(0.3);
  options.local_slam.use_online_correlative_scan_matching = true;
  options.local_slam.adaptive_rotation_prior.window_scans = 20;
  options.local_slam.adaptive_rotation_prior.min_scans = 5;
  // A prior this strong holds the biased odometry's heading, so the window's weight (not the
  // configured 0.1) visibly decides the first matches after the split.
  options.local_slam.adaptive_rotation_prior.min_weight = 200.0;
  options.local_slam.adaptive_rotation_prior.max_weight = 200.0;
  MapBuilder2D original(options, &executor);
  Feed(input, 0, split, &original);
  const MapBuilderState2D state = original.ExportState();
  ASSERT_EQ(state.local_slam.heading_corrections_rad.size(), 20u);
  MapBuilderState2D without_window = state;
  without_window.local_slam.heading_corrections_rad.clear();

  auto restored = MapBuilder2D::Restore(options, &executor, state);
  auto forgetful = MapBuilder2D::Restore(options, &executor, without_window);
  EXPECT_EQ(restored->ExportState().local_slam.heading_corrections_rad,
            state.local_slam.heading_corrections_rad);
  for (MapBuilder2D* builder : {&original, restored.get(), forgetful.get()}) {
    Feed(input, split, input.size(), builder);
    builder->Finish();
  }
  ExpectSamePoses(original.NodePoses(), restored->NodePoses());
  const auto expected = original.NodePoses();
  const auto departed = forgetful->NodePoses();
  ASSERT_EQ(departed.size(), expected.size());
  double max_difference_m = 0.0;
  for (size_t i = 0; i < expected.size(); ++i) {
    max_difference_m = std::max(
        max_difference_m, (departed[i].pose.translation() - expected[i].pose.translation()).norm());
  }
  EXPECT_GT(max_difference_m, 1e-6);
}

TEST(MapBuilderState2DTest, TrimmedGraphRestoresExactly) {
  const std::vector<Input> input = LoopInput(2.2);
  const size_t split = input.size() * 2 / 3;
  common::InlineExecutor executor;
  const MapBuilderOptions2D options = TrimmingOptions();
  MapBuilder2D original(options, &executor);
  Feed(input, 0, split, &original);
  const MapBuilderState2D state = original.ExportState();
  ASSERT_GT(state.pose_graph.stats.trimmed_submaps, 0);
  ASSERT_GT(state.pose_graph.stats.trimmed_nodes, 0);

  auto restored = MapBuilder2D::Restore(options, &executor, state);
  const MapBuilderState2D again = restored->ExportState();
  ExpectSameSubmaps(state, again);
  for (size_t s = 0; s < state.submaps.size(); ++s) {
    EXPECT_EQ(again.pose_graph.submaps[s].trimmed, state.pose_graph.submaps[s].trimmed) << s;
    EXPECT_EQ(restored->pose_graph().submaps()[s] == nullptr, state.pose_graph.submaps[s].trimmed);
  }
  Feed(input, split, input.size(), &original);
  Feed(input, split, input.size(), restored.get());
  original.Finish();
  restored->Finish();
  // Trimming goes on after the restore, the same way in both.
  EXPECT_GT(restored->pose_graph().stats().trimmed_submaps, state.pose_graph.stats.trimmed_submaps);
  EXPECT_EQ(restored->pose_graph().stats().trimmed_nodes,
            original.pose_graph().stats().trimmed_nodes);
  ExpectSamePoses(original.NodePoses(), restored->NodePoses());
}

// Taking trimmed nodes out of the graph takes memory, not information: the nodes taken merged
// with the ones kept are the run without taking any, and a state exported after taking them
// restores and continues exactly.
TEST(MapBuilderState2DTest, ArchivingTrimmedNodesKeepsTheRunAndItsCheckpoints) {
  const std::vector<Input> input = LoopInput(2.2);
  common::InlineExecutor executor;
  const MapBuilderOptions2D options = TrimmingOptions();
  MapBuilder2D plain(options, &executor);
  MapBuilder2D archiving(options, &executor);
  std::vector<MapBuilder2D::TimedPose2d> archived;
  const size_t split = input.size() * 2 / 3;
  for (size_t begin = 0; begin < split; begin += 20) {
    const size_t end = std::min(split, begin + 20);
    Feed(input, begin, end, &plain);
    Feed(input, begin, end, &archiving);
    std::vector<int> indices;
    for (const auto& node : archiving.pose_graph().TrimmedNodes()) {
      archived.push_back({node.stamp_s, node.T_map_node});
      indices.push_back(node.node);
    }
    archiving.pose_graph().RemoveTrimmedNodes(indices);
  }
  ASSERT_GT(archived.size(), 20u);
  const auto held = archiving.pose_graph().Snapshot();
  EXPECT_EQ(held->node_ids.size() + archived.size(),
            static_cast<size_t>(archiving.pose_graph().stats().nodes));
  EXPECT_TRUE(archiving.pose_graph().TrimmedNodes().empty());
  // Nodes still in use are never let go.
  archiving.pose_graph().RemoveTrimmedNodes(held->node_ids);
  EXPECT_EQ(archiving.pose_graph().Snapshot()->node_ids, held->node_ids);

  const MapBuilderState2D state = archiving.ExportState();
  EXPECT_EQ(state.pose_graph.nodes.size(), held->node_ids.size());
  EXPECT_EQ(state.pose_graph.nodes.back().index, held->node_ids.back());
  EXPECT_LT(state.pose_graph.nodes.size(), plain.ExportState().pose_graph.nodes.size());
  auto restored = MapBuilder2D::Restore(options, &executor, state);
  EXPECT_EQ(restored->pose_graph().Snapshot()->node_ids, held->node_ids);
  Feed(input, split, input.size(), &plain);
  Feed(input, split, input.size(), &archiving);
  Feed(input, split, input.size(), restored.get());
  plain.Finish();
  archiving.Finish();
  restored->Finish();

  EXPECT_EQ(archiving.pose_graph().stats().loop_closures_found,
            plain.pose_graph().stats().loop_closures_found);
  auto whole = archived;
  for (const auto& node : archiving.NodePoses()) whole.push_back(node);
  std::sort(whole.begin(), whole.end(),
            [](const auto& a, const auto& b) { return a.stamp_s < b.stamp_s; });
  ExpectSamePoses(plain.NodePoses(), whole);
  ExpectSamePoses(archiving.NodePoses(), restored->NodePoses());
}

// Holds tasks until RunAll(), so a test can export while work is deterministically in flight.
class DeferredExecutor : public common::Executor {
 public:
  void Schedule(std::function<void()> task) override { tasks_.push_back(std::move(task)); }
  void WaitIdle() override { RunAll(); }
  size_t queued() const { return tasks_.size(); }
  void RunAll() {
    while (!tasks_.empty()) {
      auto task = std::move(tasks_.front());
      tasks_.pop_front();
      task();
    }
  }

 private:
  std::deque<std::function<void()>> tasks_;
};

TEST(MapBuilderState2DTest, WorkInFlightAtExportIsRedoneAfterRestore) {
  const std::vector<Input> input = LoopInput();
  const MapBuilderOptions2D options = TestOptions(1.0);
  DeferredExecutor executor;
  MapBuilder2D original(options, &executor);
  // Export at the first scan after which a precomputation, searches and an optimisation are
  // all still queued.
  size_t split = 0;
  MapBuilderState2D state;
  for (size_t i = 0; i < input.size() && split == 0; ++i) {
    Feed(input, i, i + 1, &original);
    state = original.ExportState();
    const bool precomputing = std::any_of(
        state.pose_graph.submaps.begin(), state.pose_graph.submaps.end(),
        [](const PoseGraphState2D::Submap& s) { return s.finished && !s.matcher_ready; });
    if (precomputing && !state.pose_graph.searches_in_flight.empty() &&
        state.pose_graph.optimization_pending) {
      split = i + 1;
    }
    executor.RunAll();
  }
  ASSERT_GT(split, 0u) << "no scan left all three kinds of work queued";
  DeferredExecutor restored_executor;
  auto restored = MapBuilder2D::Restore(options, &restored_executor, state);
  restored_executor.RunAll();
  EXPECT_EQ(restored->pose_graph().stats().loop_closure_searches,
            original.pose_graph().stats().loop_closure_searches);
  EXPECT_EQ(restored->pose_graph().stats().loop_closures_found,
            original.pose_graph().stats().loop_closures_found);
  EXPECT_EQ(restored->pose_graph().stats().optimizations,
            original.pose_graph().stats().optimizations);
  for (size_t i = split; i < input.size(); ++i) {
    Feed(input, i, i + 1, &original);
    executor.RunAll();
    Feed(input, i, i + 1, restored.get());
    restored_executor.RunAll();
  }
  original.Finish();
  restored->Finish();
  const auto expected = original.NodePoses();
  const auto actual = restored->NodePoses();
  ASSERT_EQ(actual.size(), expected.size());
  // The redone searches finish in another order, so constraints reach the solver (10
  // iterations per run) in another order: close, not bit for bit; 1 cm / 0.5 deg.
  double max_m = 0.0, max_rad = 0.0;
  for (size_t i = 0; i < actual.size(); ++i) {
    max_m = std::max(max_m, (actual[i].pose.translation() - expected[i].pose.translation()).norm());
    max_rad = std::max(max_rad, std::abs(common::NormalizeAngle(actual[i].pose.angle_rad() -
                                                                expected[i].pose.angle_rad())));
  }
  std::printf("restored after export at scan %zu: max difference %.5f m, %.4f deg\n", split,
              max_m, common::RadToDeg(max_rad));
  EXPECT_LT(max_m, 0.01);
  EXPECT_LT(max_rad, common::DegToRad(0.5));
}

TEST(MapBuilderState2DTest, ExportWhileTheOptimiserRunsInTheBackground) {
  const std::vector<Input> input = LoopInput();
  common::ThreadPool pool(2);
  const MapBuilderOptions2D options = TestOptions(1.0);
  MapBuilder2D original(options, &pool);
  // Exports right after scans, with searches and optimisations likely still in flight.
  MapBuilderState2D state;
  const size_t split = input.size() / 2;
  for (size_t i = 0; i < split; ++i) {
    Feed(input, i, i + 1, &original);
    state = original.ExportState();
  }
  auto restored = MapBuilder2D::Restore(options, &pool, state);
  Feed(input, split, input.size(), restored.get());
  restored->Finish();
  const auto poses = restored->NodePoses();
  ASSERT_EQ(poses.size(), input.size());
  EXPECT_GT(restored->pose_graph().stats().loop_closures_found, 0);
  const common::Rigid2d truth =
      TruePose(0).inverse() * TruePose(static_cast<int>(input.size()) - 1);
  const common::Rigid2d estimate = poses.front().pose.inverse() * poses.back().pose;
  // Same options and bound as the uninterrupted thread-pool run in map_builder_2d_test.
  EXPECT_LT((truth.translation() - estimate.translation()).norm(), 0.08);
}

}  // namespace
}  // namespace pose_graph
}  // namespace fusemap
