#include "fusemap/pose_graph/pose_graph_2d.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <vector>

#include "fusemap/common/math.h"
#include "testing/drifting_arc_drive.h"
#include "testing/synthetic_room.h"
#include "fusemap/sensor/range_data_builder.h"
#include "fusemap/sensor/voxel_filter.h"

namespace fusemap {
namespace pose_graph {
namespace {

using test_world::kArcRadiusM;
using test_world::Room;
using test_world::Segment;
using test_world::SimulateRangeData;

constexpr double kStepM = 0.15;

common::Rigid2d TruePose(int i) { return test_world::ArcPose(i, kStepM); }

// 1.1 turns of the arc: the end revisits the start.
constexpr int kLapAndATenthNodes = static_cast<int>(1.1 * 2.0 * common::kPi * kArcRadiusM / kStepM);

PoseGraphOptions2D TestOptions(int optimize_every_n_nodes) {
  PoseGraphOptions2D options;
  options.optimize_every_n_nodes = optimize_every_n_nodes;
  options.constraint_builder.sampling_ratio = 1.0;
  options.constraint_builder.max_constraint_distance_m = 3.0;
  options.constraint_builder.fast_correlative_scan_matcher.linear_search_window_m = 1.0;
  options.constraint_builder.fast_correlative_scan_matcher.angular_search_window_rad =
      common::DegToRad(15.0);
  return options;
}

struct RunResult {
  PoseGraph2D::Stats stats;
  std::vector<common::Rigid2d> T_map_nodes;
  std::vector<common::Rigid2d> T_local_nodes;
  int callbacks = 0;
  int moved_submaps = 0;
  // TakeSubmapPlacements after every node and after the final optimisation: how often each
  // submap was handed out as new, and the pose it was last handed out at.
  std::map<int, int> placed_new;
  std::map<int, common::Rigid2d> placed;
  std::vector<common::Rigid2d> T_map_submaps;
  // The loop closures of the final graph, by node then submap.
  std::vector<Constraint2D> loop_closures;
  int compacted_submaps = 0;  // held deflated at the end
  // PathBetween(last node, submap 0) at the end, and the path along the chain of nodes.
  double last_node_to_first_submap_m = -1.0;
  double last_node_to_first_submap_along_chain_m = -1.0;
};

// Local SLAM with a known drift (testing/drifting_arc_drive.h).
RunResult RunGraph(int num_nodes, const PoseGraphOptions2D& options, common::Executor* executor) {
  test_world::DriftingArcDrive drive(kStepM);
  RunResult result;
  PoseGraph2D graph(options, executor);
  graph.AddSubmapsMovedCallback([&result](const std::vector<SubmapMove>& moves) {
    ++result.callbacks;
    result.moved_submaps += static_cast<int>(moves.size());
  });
  for (int i = 0; i < num_nodes; ++i) {
    const test_world::DriftingArcDrive::Step step = drive.Next();
    EXPECT_EQ(graph.AddNode(0.1 * i, step.T_local_node, step.filtered_cloud,
                            step.insertion_submaps),
              i);
    result.T_local_nodes.push_back(step.T_local_node);
    for (const SubmapPlacement& p : graph.TakeSubmapPlacements()) {
      result.placed_new[p.submap] += p.is_new;
      result.placed[p.submap] = p.T_map_submap;
    }
  }
  graph.RunFinalOptimization();
  for (const SubmapPlacement& p : graph.TakeSubmapPlacements()) {
    result.placed_new[p.submap] += p.is_new;
    result.placed[p.submap] = p.T_map_submap;
  }
  result.T_map_submaps = graph.Snapshot()->T_map_submaps;
  for (const auto& submap : graph.submaps()) result.compacted_submaps += submap && submap->compacted();
  result.stats = graph.stats();
  const auto snapshot = graph.Snapshot();
  result.T_map_nodes = snapshot->T_map_nodes;
  std::vector<std::shared_ptr<const mapping::Submap2D>> unused_submaps;
  for (const Constraint2D& c : graph.ExportState(&unused_submaps).constraints) {
    if (c.tag == Constraint2D::kInterSubmap) result.loop_closures.push_back(c);
  }
  std::sort(result.loop_closures.begin(), result.loop_closures.end(),
            [](const Constraint2D& a, const Constraint2D& b) {
              return std::make_pair(a.node, a.submap) < std::make_pair(b.node, b.submap);
            });
  result.last_node_to_first_submap_m = graph.PathBetween(num_nodes - 1, 0).value_or(-1.0);
  double path_m = 0.0;  // submap 0 holds node 0; the drive goes on from it
  for (int i = 1; i < num_nodes; ++i) {
    path_m += (result.T_local_nodes[i].translation() - result.T_local_nodes[i - 1].translation())
                  .norm();
  }
  result.last_node_to_first_submap_along_chain_m = path_m;
  EXPECT_EQ(graph.node_stamps_s().size(), static_cast<size_t>(num_nodes));
  return result;
}

RunResult RunGraph(int num_nodes, int optimize_every_n_nodes, common::Executor* executor) {
  return RunGraph(num_nodes, TestOptions(optimize_every_n_nodes), executor);
}

// End-point error after expressing both trajectories relative to their first pose.
double EndErrorM(const std::vector<common::Rigid2d>& poses) {
  const common::Rigid2d truth = TruePose(0).inverse() * TruePose(poses.size() - 1);
  const common::Rigid2d estimate = poses.front().inverse() * poses.back();
  return (truth.translation() - estimate.translation()).norm();
}

TEST(PoseGraph2DTest, LocalOnlyKeepsLocalPosesAndSearchesNothing) {
  common::InlineExecutor executor;
  const RunResult run = RunGraph(25, 0, &executor);
  EXPECT_EQ(run.stats.nodes, 25);
  EXPECT_EQ(run.stats.submaps, 3);  // new submaps start at nodes 0, 10, 20
  // Nodes 0-9 go into one submap, the rest into two.
  EXPECT_EQ(run.stats.intra_constraints, 10 + 2 * 15);
  EXPECT_EQ(run.stats.loop_closure_searches, 0);
  EXPECT_EQ(run.stats.optimizations, 0);
  EXPECT_EQ(run.callbacks, 0);
  // Submap 0 finished with node 19 and left local SLAM at node 20: held deflated since.
  EXPECT_EQ(run.stats.finished_submaps, 1);
  EXPECT_EQ(run.compacted_submaps, 1);
  ASSERT_EQ(run.T_map_nodes.size(), 25u);
  for (size_t i = 0; i < run.T_map_nodes.size(); ++i) {
    // The first node defines T_map_local = identity, so map poses are the local ones.
    EXPECT_LT((run.T_map_nodes[i].translation() - run.T_local_nodes[i].translation()).norm(), 1e-9);
  }
}

TEST(PoseGraph2DTest, LoopClosureReducesDrift) {
  const int num_nodes = kLapAndATenthNodes;
  common::InlineExecutor executor;
  const RunResult run = RunGraph(num_nodes, 10, &executor);
  const double drift_m = EndErrorM(run.T_local_nodes);
  const double optimized_m = EndErrorM(run.T_map_nodes);
  std::printf("nodes %d, searches %d, loop closures %d, optimisations %d; end error local %.3f m,"
              " optimised %.3f m\n",
              num_nodes, run.stats.loop_closure_searches, run.stats.loop_closures_found,
              run.stats.optimizations, drift_m, optimized_m);
  EXPECT_GT(run.stats.finished_submaps, 5);
  // Every finished submap but one local SLAM may still hold is deflated.
  EXPECT_GE(run.compacted_submaps, run.stats.finished_submaps - 1);
  EXPECT_GT(run.stats.loop_closures_found, 0);
  EXPECT_GE(run.stats.optimizations, num_nodes / 10);
  EXPECT_GT(drift_m, 0.3);
  EXPECT_LT(optimized_m, 0.08);
  EXPECT_GT(run.callbacks, 0);
  EXPECT_GT(run.moved_submaps, 0);
}

TEST(PoseGraph2DTest, SubmapPlacementsFollowEveryOptimisation) {
  common::InlineExecutor executor;
  const RunResult result = RunGraph(80, 10, &executor);
  ASSERT_GT(result.stats.optimizations, 1);
  ASSERT_EQ(result.placed.size(), result.T_map_submaps.size());
  for (size_t i = 0; i < result.T_map_submaps.size(); ++i) {
    const int submap = static_cast<int>(i);
    EXPECT_EQ(result.placed_new.at(submap), 1) << "submap " << i;
    // Whoever follows the placements holds every submap within the one threshold.
    EXPECT_FALSE(SubmapMoved(result.placed.at(submap), result.T_map_submaps[i])) << "submap " << i;
  }
  // Optimisations moved submaps, and the placements re-placed them.
  EXPECT_GT(result.moved_submaps, 0);
}

// A 1.1-turn drive on a thread pool: every search finished, the loop closed.
RunResult ExpectThreadPoolRunClosesTheLoop(const PoseGraphOptions2D& options) {
  const int num_nodes = kLapAndATenthNodes;
  common::ThreadPool pool(2);
  const RunResult run = RunGraph(num_nodes, options, &pool);
  EXPECT_EQ(run.stats.nodes, num_nodes);
  EXPECT_EQ(run.stats.pending_searches, 0);  // RunFinalOptimization waited for all of them
  // ...and then released the precomputation grids.
  EXPECT_EQ(run.stats.matchers, 0);
  EXPECT_EQ(run.stats.matcher_bytes, 0u);
  EXPECT_GT(run.stats.max_matcher_bytes, 0u);
  EXPECT_GT(run.stats.max_pending_searches, 0);
  EXPECT_GT(run.stats.loop_closures_found, 0);
  EXPECT_GT(run.stats.optimizations, 0);
  EXPECT_LT(EndErrorM(run.T_map_nodes), 0.08);
  return run;
}

TEST(PoseGraph2DTest, ThreadPoolRunFindsLoopClosures) {
  ExpectThreadPoolRunClosesTheLoop(TestOptions(10));
}

TEST(PoseGraph2DTest, MatcherMemoryBudgetChangesWhenSearchesRunNotWhatTheyFind) {
  const int num_nodes = kLapAndATenthNodes;
  common::InlineExecutor executor;
  const RunResult unbounded = RunGraph(num_nodes, TestOptions(10), &executor);
  PoseGraphOptions2D tight = TestOptions(10);
  // Smaller than one submap's grids: only the one just built or rebuilt is held.
  tight.matcher_memory_budget_mb = 1e-3;
  const RunResult bounded = RunGraph(num_nodes, tight, &executor);
  EXPECT_EQ(unbounded.stats.matcher_evictions, 0);
  EXPECT_EQ(unbounded.stats.matcher_builds, unbounded.stats.finished_submaps);
  EXPECT_GT(bounded.stats.matcher_evictions, 0);
  EXPECT_GT(bounded.stats.matcher_builds, bounded.stats.finished_submaps);
  EXPECT_EQ(bounded.stats.max_matchers, 1);
  EXPECT_EQ(unbounded.stats.max_matchers, unbounded.stats.finished_submaps);
  EXPECT_LT(bounded.stats.max_matcher_bytes, unbounded.stats.max_matcher_bytes);
  EXPECT_EQ(bounded.stats.pending_searches, 0);
  EXPECT_EQ(bounded.stats.loop_closure_searches, unbounded.stats.loop_closure_searches);
  EXPECT_EQ(bounded.stats.loop_closures_found, unbounded.stats.loop_closures_found);
  // The same node-submap pairs matched. Searches that wait for rebuilt grids finish in another
  // order, so the constraints reach the optimiser in another order; its rounding moves the
  // estimates the later searches start from by millimetres, and the branch and bound, which
  // steps by a cell from where it starts, can land a cell (0.05 m here) or an angular step
  // away.
  ASSERT_EQ(bounded.loop_closures.size(), unbounded.loop_closures.size());
  for (size_t i = 0; i < bounded.loop_closures.size(); ++i) {
    const Constraint2D& a = bounded.loop_closures[i];
    const Constraint2D& b = unbounded.loop_closures[i];
    EXPECT_EQ(a.node, b.node);
    EXPECT_EQ(a.submap, b.submap);
    EXPECT_LT((a.T_submap_node.translation() - b.T_submap_node.translation()).norm(), 0.05)
        << "closure " << i;
    EXPECT_NEAR(a.T_submap_node.angle_rad(), b.T_submap_node.angle_rad(), 0.02)
        << "closure " << i;
  }
  ASSERT_EQ(bounded.T_map_nodes.size(), unbounded.T_map_nodes.size());
  for (size_t i = 0; i < bounded.T_map_nodes.size(); ++i) {
    EXPECT_LT((bounded.T_map_nodes[i].translation() - unbounded.T_map_nodes[i].translation())
                  .norm(),
              0.01)
        << "node " << i;
    EXPECT_NEAR(bounded.T_map_nodes[i].angle_rad(), unbounded.T_map_nodes[i].angle_rad(), 0.005)
        << "node " << i;
  }
}

TEST(PoseGraph2DTest, ThreadPoolRunWithinATinyMatcherBudgetClosesTheLoop) {
  PoseGraphOptions2D tight = TestOptions(10);
  tight.matcher_memory_budget_mb = 1e-3;
  EXPECT_GT(ExpectThreadPoolRunClosesTheLoop(tight).stats.matcher_evictions, 0);
}

TEST(PoseGraph2DTest, SearchesBeyondTheQueueCapAreSkippedAndCounted) {
  const int num_nodes = kLapAndATenthNodes;
  common::InlineExecutor executor;
  const RunResult unbounded = RunGraph(num_nodes, TestOptions(10), &executor);
  PoseGraphOptions2D capped = TestOptions(10);
  capped.max_pending_searches = 1;
  const RunResult run = RunGraph(num_nodes, capped, &executor);
  // The inline executor runs a node's searches after AddNode queued them all, so without the
  // cap several are pending at once.
  EXPECT_GT(unbounded.stats.max_pending_searches, 1);
  EXPECT_EQ(unbounded.stats.searches_skipped, 0);
  EXPECT_EQ(run.stats.max_pending_searches, 1);
  EXPECT_GT(run.stats.searches_skipped, 0);
  EXPECT_LT(run.stats.loop_closure_searches, unbounded.stats.loop_closure_searches);
}

// A pool whose workers are all busy searching until the end: searches wait (in the order they
// came) until WaitIdle; the upkeep that goes ahead of them (precomputation, optimisation) runs
// at once.
class SearchesWaitExecutor : public common::Executor {
 public:
  void Schedule(std::function<void()> task) override { held_.push_back(std::move(task)); }
  void ScheduleFirst(std::function<void()> task) override { task(); }
  void WaitIdle() override {
    for (size_t i = 0; i < held_.size(); ++i) held_[i]();
    held_.clear();
  }

 private:
  std::vector<std::function<void()>> held_;
};

TEST(PoseGraph2DTest, AFullQueueKeepsTheSearchesOfTheNewestNodes) {
  const int num_nodes = kLapAndATenthNodes;
  PoseGraphOptions2D capped = TestOptions(10);
  capped.max_pending_searches = 20;
  SearchesWaitExecutor executor;
  const RunResult run = RunGraph(num_nodes, capped, &executor);
  EXPECT_GT(run.stats.searches_skipped, 0);
  EXPECT_EQ(run.stats.loop_closure_searches, 20);
  ASSERT_FALSE(run.loop_closures.empty());
  // The lap's end, where it closes; first come, first served would have kept the searches of
  // the first nodes near a finished submap instead (none of which closes the loop).
  EXPECT_GE(run.loop_closures.front().node, num_nodes - 10);
}

// The drive's local SLAM drifts > 0.3 m over the lap. Allowed no more correction than 2 cm, the
// closures at the lap's end (which ask for the drift back) are refused and counted, and the
// loop stays open; the default bound (0.5 m + 2 % of the path) lets them all through.
TEST(PoseGraph2DTest, LoopClosuresBeyondDriftAreRefusedAndCounted) {
  const int num_nodes = kLapAndATenthNodes;
  common::InlineExecutor executor;
  const RunResult defaults = RunGraph(num_nodes, TestOptions(10), &executor);
  PoseGraphOptions2D strict = TestOptions(10);
  strict.constraint_builder.max_correction_m = 0.02;
  strict.constraint_builder.max_correction_per_path_m = 0.0;
  const RunResult run = RunGraph(num_nodes, strict, &executor);
  std::printf("loop closures %d (default bound) vs %d, %d beyond drift; end error %.3f vs %.3f m\n",
              defaults.stats.loop_closures_found, run.stats.loop_closures_found,
              run.stats.loop_closures_beyond_drift, EndErrorM(defaults.T_map_nodes),
              EndErrorM(run.T_map_nodes));
  EXPECT_EQ(defaults.stats.loop_closures_beyond_drift, 0);
  EXPECT_LT(EndErrorM(defaults.T_map_nodes), 0.08);
  EXPECT_GT(run.stats.loop_closures_beyond_drift, 0);
  EXPECT_LT(run.stats.loop_closures_found, defaults.stats.loop_closures_found);
  EXPECT_GT(EndErrorM(run.T_map_nodes), 0.2);
}

// Drift accrues only since the graph last tied two places together: once the lap's closures
// are solved, the path the drift bound allows for between the last node and the first submap is
// the way round through them, not the lap.
TEST(PoseGraph2DTest, SolvedLoopClosuresShortenThePathTheDriftBoundAllowsFor) {
  const int num_nodes = kLapAndATenthNodes;
  common::InlineExecutor executor;
  const RunResult local_only = RunGraph(num_nodes, 0, &executor);
  const RunResult closed = RunGraph(num_nodes, 10, &executor);
  std::printf("last node to submap 0: %.2f m without closures, %.2f m with %d (chain %.2f m)\n",
              local_only.last_node_to_first_submap_m, closed.last_node_to_first_submap_m,
              closed.stats.loop_closures_found, closed.last_node_to_first_submap_along_chain_m);
  ASSERT_GT(closed.stats.loop_closures_found, 0);
  // Submap 0 holds the first nodes, so along the chain this is nearly the whole drive.
  EXPECT_GT(local_only.last_node_to_first_submap_m,
            0.8 * local_only.last_node_to_first_submap_along_chain_m);
  EXPECT_LE(local_only.last_node_to_first_submap_m,
            local_only.last_node_to_first_submap_along_chain_m + 1e-9);
  EXPECT_GE(closed.last_node_to_first_submap_m, 0.0);
  EXPECT_LT(closed.last_node_to_first_submap_m,
            0.2 * closed.last_node_to_first_submap_along_chain_m);
}

TEST(PoseGraph2DTest, VerifiedLoopClosuresStillCloseTheLoop) {
  const int num_nodes = kLapAndATenthNodes;
  common::InlineExecutor executor;
  PoseGraphOptions2D options = TestOptions(10);
  options.loop_closure_verification.min_agreeing_closures = 2;
  const RunResult unverified = RunGraph(num_nodes, 10, &executor);
  const RunResult run = RunGraph(num_nodes, options, &executor);
  std::printf("loop closures %d verified of %d (%d left unverified)\n",
              run.stats.loop_closures_found, unverified.stats.loop_closures_found,
              run.stats.loop_closure_candidates);
  // Right matches of neighbouring nodes agree, so most are accepted.
  EXPECT_GT(run.stats.loop_closures_found, unverified.stats.loop_closures_found / 2);
  EXPECT_LT(EndErrorM(run.T_map_nodes), 0.08);
}

// A search widened beyond the configured window (LoopSearchWindowM) reaches more places a scan
// fits by chance: its match waits as a candidate until another closure agrees with it, even
// with verification off. Here every search is widened (max_correction_m 1.5 m over a 1 m
// window): the first match waits, and the lap still closes once they agree. With the window
// held at 1 m the first match is taken at once.
TEST(PoseGraph2DTest, MatchesOfWidenedSearchesWaitForAnAgreeingClosure) {
  const auto run = [](double max_linear_search_window_m, PoseGraph2D::Stats* at_first_match) {
    PoseGraphOptions2D options = TestOptions(10);
    ASSERT_FALSE(options.loop_closure_verification.enabled());
    options.constraint_builder.max_correction_m = 1.5;
    options.constraint_builder.max_linear_search_window_m = max_linear_search_window_m;
    common::InlineExecutor executor;
    PoseGraph2D graph(options, &executor);
    test_world::DriftingArcDrive drive(kStepM);
    bool matched = false;
    for (int i = 0; i < kLapAndATenthNodes; ++i) {
      const test_world::DriftingArcDrive::Step step = drive.Next();
      graph.AddNode(0.1 * i, step.T_local_node, step.filtered_cloud, step.insertion_submaps);
      const PoseGraph2D::Stats stats = graph.stats();
      if (!matched && stats.loop_closures_found + stats.loop_closure_candidates > 0) {
        matched = true;
        *at_first_match = stats;
      }
    }
    graph.RunFinalOptimization();
    ASSERT_TRUE(matched);
    const PoseGraph2D::Stats stats = graph.stats();
    std::printf("window up to %.1f m: %d accepted, %d waiting at the end\n",
                max_linear_search_window_m, stats.loop_closures_found,
                stats.loop_closure_candidates);
    EXPECT_GT(stats.loop_closures_found, 0);
    EXPECT_LT(EndErrorM(graph.Snapshot()->T_map_nodes), 0.08);
  };
  PoseGraph2D::Stats widened, fixed;
  run(2.0, &widened);
  EXPECT_EQ(widened.loop_closures_found, 0);
  EXPECT_GT(widened.loop_closure_candidates, 0);
  run(1.0, &fixed);
  EXPECT_GT(fixed.loop_closures_found, 0);
  EXPECT_EQ(fixed.loop_closure_candidates, 0);
}

TEST(PoseGraph2DTest, OptionsValidation) {
  std::string error;
  PoseGraphOptions2D options;
  EXPECT_TRUE(options.IsValid(&error)) << error;
  options.optimize_every_n_nodes = -1;
  EXPECT_FALSE(options.IsValid(&error));
  options.optimize_every_n_nodes = 10;
  options.matcher_rotation_weight = 0.0;
  EXPECT_FALSE(options.IsValid(&error));
  options.matcher_rotation_weight = 1.0;
  options.loop_closure_verification.max_node_gap = 0;
  EXPECT_FALSE(options.IsValid(&error));
  options.loop_closure_verification.max_node_gap =
      PoseGraphOptions2D().loop_closure_verification.max_node_gap;
  for (double fraction : {0.0, 1.5}) {
    options.linked_unmeasured_weight_fraction = fraction;
    EXPECT_FALSE(options.IsValid(&error));
    EXPECT_NE(error.find("linked_unmeasured_weight_fraction"), std::string::npos) << error;
  }
  options.linked_unmeasured_weight_fraction = 1.0;
  EXPECT_TRUE(options.IsValid(&error)) << error;
}

}  // namespace
}  // namespace pose_graph
}  // namespace fusemap
