// PoseGraph2D's loop-constraint API (pose_graph_2d_loops.cc).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <set>
#include <vector>

#include "fusemap/common/math.h"
#include "fusemap/mapping/submap_2d.h"
#include "fusemap/pose_graph/pose_graph_2d.h"
#include "fusemap/sensor/range_data_builder.h"
#include "fusemap/sensor/voxel_filter.h"
#include "testing/drifting_arc_drive.h"
#include "testing/synthetic_room.h"

namespace fusemap {
namespace pose_graph {
namespace {

constexpr double kStepM = 0.15;
const int kLoopNodes =
    static_cast<int>(1.1 * 2.0 * common::kPi * test_world::kArcRadiusM / kStepM);

common::Rigid2d TruePose(int i) { return test_world::ArcPose(i, kStepM); }

PoseGraphOptions2D TestOptions(bool laser_loops) {
  PoseGraphOptions2D options;
  options.optimize_every_n_nodes = 10;
  options.constraint_builder.sampling_ratio = 1.0;
  // Without laser loops no node is ever close enough to a finished submap to be searched.
  options.constraint_builder.max_constraint_distance_m = laser_loops ? 3.0 : 1e-6;
  options.constraint_builder.fast_correlative_scan_matcher.linear_search_window_m = 1.0;
  options.constraint_builder.fast_correlative_scan_matcher.angular_search_window_rad =
      common::DegToRad(15.0);
  return options;
}

// Drives a graph around the room's arc with the drift of pose_graph_2d_test (1 % too much
// translation, 0.1 deg too much yaw a step); `after_node` runs after every AddNode.
class LoopRun {
 public:
  explicit LoopRun(bool laser_loops) : graph_(TestOptions(laser_loops), &executor_) {}

  template <typename F>
  void Drive(int num_nodes, F&& after_node) {
    for (int i = 0; i < num_nodes; ++i) {
      const test_world::DriftingArcDrive::Step step = drive_.Next();
      graph_.AddNode(0.1 * i, step.T_local_node, step.filtered_cloud, step.insertion_submaps);
      after_node(i);
    }
  }
  void Drive(int num_nodes) {
    Drive(num_nodes, [](int) {});
  }

  // End-point error against the truth, both trajectories relative to their first pose.
  double EndErrorM() const {
    const auto snapshot = graph_.Snapshot();
    const auto& poses = snapshot->T_map_nodes;
    const common::Rigid2d truth = TruePose(0).inverse() * TruePose(poses.size() - 1);
    const common::Rigid2d estimate = poses.front().inverse() * poses.back();
    return (truth.translation() - estimate.translation()).norm();
  }
  // The true pose of node `node` in submap 0's frame (local SLAM barely drifted while it was
  // built, so its local pose is close to the truth).
  common::Rigid2d TrueSubmap0Node(int node) const { return drive_.TrueInFirstSubmap(node); }

  PoseGraph2D& graph() { return graph_; }

 private:
  common::InlineExecutor executor_;
  PoseGraph2D graph_;
  test_world::DriftingArcDrive drive_{kStepM};
};

ExternalLoopConstraint2D Visual(int node, int submap, const common::Rigid2d& T_submap_node) {
  ExternalLoopConstraint2D c;
  c.node = node;
  c.submap = submap;
  c.T_submap_node = T_submap_node;
  c.translation_weight = 1.1e4;
  c.rotation_weight = 1e5;
  c.source = Constraint2D::kVisual;
  return c;
}

TEST(PoseGraph2DLoopsTest, ReportsEachAcceptedLaserClosureOnceWithIdAndScore) {
  LoopRun run(/*laser_loops=*/true);
  run.graph().ReportLoopClosures();
  std::vector<LoopClosure2D> taken;
  run.Drive(kLoopNodes, [&](int) {
    for (const LoopClosure2D& c : run.graph().TakeNewLoopClosures()) taken.push_back(c);
  });
  run.graph().RunFinalOptimization();
  ASSERT_FALSE(taken.empty());
  EXPECT_TRUE(run.graph().TakeNewLoopClosures().empty());
  EXPECT_EQ(static_cast<int>(taken.size()), run.graph().stats().loop_closures_found);
  std::set<int> ids;
  for (const LoopClosure2D& c : taken) {
    EXPECT_TRUE(ids.insert(c.id).second) << "id " << c.id << " twice";
    EXPECT_GT(c.laser_score, 0.0);
  }
  for (const Constraint2D& c : run.graph().LoopConstraints()) {
    EXPECT_EQ(c.source, Constraint2D::kLaser);
    EXPECT_EQ(ids.count(c.loop_id), 1u);
  }
}

TEST(PoseGraph2DLoopsTest, WithoutReportingNothingIsKept) {
  LoopRun run(/*laser_loops=*/true);
  run.Drive(kLoopNodes);
  EXPECT_GT(run.graph().stats().loop_closures_found, 0);
  EXPECT_TRUE(run.graph().TakeNewLoopClosures().empty());
}

TEST(PoseGraph2DLoopsTest, ForcedConstraintsPullTheRevisitsToTheirMeasurement) {
  LoopRun without(/*laser_loops=*/false);
  without.Drive(kLoopNodes);
  without.graph().RunFinalOptimization();
  const double drift_m = without.EndErrorM();

  LoopRun run(/*laser_loops=*/false);
  const int last = kLoopNodes - 1;
  run.Drive(kLoopNodes);
  // A few revisits, as keyframes a few per metre would give (the graph's Huber loss makes one
  // constraint against a long chain count little, for laser closures as for these).
  std::vector<int> ids;
  for (int node = last - 20; node <= last; ++node) {
    ids.push_back(run.graph().AddLoopConstraint(Visual(node, 0, run.TrueSubmap0Node(node))));
    ASSERT_GE(ids.back(), 0);
  }
  run.graph().RunFinalOptimization();
  std::printf("end error without a loop %.3f m, with the forced one %.3f m\n", drift_m,
              run.EndErrorM());
  EXPECT_GT(drift_m, 0.3);
  // The revisits now stand where they were measured; the rest of the drift goes where the
  // graph's weights put it (stiff local-SLAM motion, soft node-in-submap ties).
  EXPECT_LT(run.EndErrorM(), 0.6 * drift_m);
  const std::optional<common::Rigid2d> T_submap_node = run.graph().T_submap_node(0, last);
  ASSERT_TRUE(T_submap_node);
  EXPECT_LT((T_submap_node->translation() - run.TrueSubmap0Node(last).translation()).norm(), 0.05);
  const std::vector<Constraint2D> loops = run.graph().LoopConstraints();
  ASSERT_EQ(loops.size(), ids.size());
  for (size_t i = 0; i < ids.size(); ++i) {
    EXPECT_EQ(loops[i].loop_id, ids[i]);
    EXPECT_EQ(loops[i].source, Constraint2D::kVisual);
  }
}

TEST(PoseGraph2DLoopsTest, ReplaceAndRemoveChangeWhatTheOptimisationSees) {
  LoopRun run(/*laser_loops=*/false);
  const int last = kLoopNodes - 1;
  run.Drive(kLoopNodes);
  // Wrong measurements first (1 m off), then the override with the right ones.
  std::vector<int> ids;
  for (int node = last - 20; node <= last; ++node) {
    const common::Rigid2d wrong = run.TrueSubmap0Node(node) * common::Rigid2d({1.0, 0.0}, 0.0);
    ids.push_back(run.graph().AddLoopConstraint(Visual(node, 0, wrong)));
    ASSERT_GE(ids.back(), 0);
    ASSERT_TRUE(run.graph().ReplaceLoopConstraint(ids.back(),
                                                  Visual(node, 0, run.TrueSubmap0Node(node))));
    ASSERT_TRUE(run.graph().SetLoopConstraintSource(ids.back(), Constraint2D::kBoth));
  }
  run.graph().RunFinalOptimization();
  const double corrected_m = run.EndErrorM();
  EXPECT_LT((run.graph().T_submap_node(0, last)->translation() -
             run.TrueSubmap0Node(last).translation()).norm(),
            0.05);
  EXPECT_EQ(run.graph().LoopConstraints().at(0).source, Constraint2D::kBoth);

  for (size_t i = 1; i < ids.size(); ++i) EXPECT_TRUE(run.graph().RemoveLoopConstraint(ids[i]));
  const int id = ids[0];
  const common::Rigid2d wrong;
  EXPECT_TRUE(run.graph().RemoveLoopConstraint(id));
  EXPECT_FALSE(run.graph().RemoveLoopConstraint(id));
  EXPECT_FALSE(run.graph().ReplaceLoopConstraint(id, Visual(last, 0, wrong)));
  EXPECT_FALSE(run.graph().SetLoopConstraintSource(id, Constraint2D::kLaser));
  EXPECT_TRUE(run.graph().LoopConstraints().empty());
  // Local SLAM's motion alone again: the drift comes back.
  run.graph().RunFinalOptimization();
  EXPECT_GT(run.EndErrorM(), corrected_m + 0.1);
}

TEST(PoseGraph2DLoopsTest, RefusesUnknownNodesSubmapsAndTheNodesOwnSubmap) {
  LoopRun run(/*laser_loops=*/false);
  run.Drive(25);
  const common::Rigid2d pose;
  EXPECT_EQ(run.graph().AddLoopConstraint(Visual(99, 0, pose)), -1);
  EXPECT_EQ(run.graph().AddLoopConstraint(Visual(24, 99, pose)), -1);
  EXPECT_EQ(run.graph().AddLoopConstraint(Visual(3, 0, pose)), -1);  // node 3 is in submap 0
  EXPECT_GE(run.graph().AddLoopConstraint(Visual(24, 0, pose)), 0);
  EXPECT_FALSE(run.graph().T_submap_node(99, 3));
  EXPECT_FALSE(run.graph().T_submap_node(0, 99));
  EXPECT_TRUE(run.graph().T_submap_node(0, 3));
}

// Local SLAM along a corridor of two plain walls longer than the laser's range, with the
// odometry's scale error (every step 3 % too long) that such scans cannot correct.
class StretchedCorridorRun {
 public:
  static constexpr double kStepM = 0.1;
  static constexpr double kStretch = 1.03;

  StretchedCorridorRun(double linked_unmeasured_weight_fraction,
                       std::vector<test_world::Segment> walls = Corridor())
      : graph_(Options(linked_unmeasured_weight_fraction), &executor_), walls_(std::move(walls)) {
    mapping::SubmapsOptions submap_options;
    submap_options.num_range_data = 20;
    active_ = std::make_unique<mapping::ActiveSubmaps2D>(submap_options);
    filter_.max_length_m = 0.9f;
    filter_.min_num_points = 100;
  }

  static std::vector<test_world::Segment> Corridor() {
    return {{{-100.0, -1.0}, {100.0, -1.0}}, {{-100.0, 1.0}, {100.0, 1.0}}};
  }
  static common::Rigid2d TruePose(int i) { return common::Rigid2d(kStepM * i, 0.0, 0.0); }

  void Drive(int num_nodes) {
    for (int i = 0; i < num_nodes; ++i) {
      const common::Rigid2d T_local_node(kStretch * kStepM * i, 0.0, 0.0);
      const sensor::RangeData data = test_world::SimulateRangeData(walls_, TruePose(i));
      const auto submaps = active_->InsertRangeData(sensor::TransformRangeData(data, T_local_node));
      graph_.AddNode(0.1 * i, T_local_node, sensor::AdaptiveVoxelFilter(data.returns, filter_),
                     submaps);
    }
  }
  // The camera's motion between every `every`-th node, exact, at translation_weight (2e5: a
  // link the verifier measured to 1 mm).
  int AddTrueLinks(int num_nodes, int every, double translation_weight = 2e5) {
    int added = 0;
    for (int from = 0; from + every < num_nodes; from += every) {
      NodeLink2D link;
      link.from = from;
      link.to = from + every;
      link.T_from_to = TruePose(from).inverse() * TruePose(from + every);
      link.translation_weight = translation_weight;
      link.rotation_weight = 1e4;
      added += graph_.AddNodeLink(link);
    }
    return added;
  }
  double FirstToLastM() {
    const auto snapshot = graph_.Snapshot();
    return (snapshot->T_map_nodes.back().translation() -
            snapshot->T_map_nodes.front().translation())
        .norm();
  }
  PoseGraph2D& graph() { return graph_; }

 private:
  static PoseGraphOptions2D Options(double linked_unmeasured_weight_fraction) {
    PoseGraphOptions2D options = TestOptions(/*laser_loops=*/false);
    options.linked_unmeasured_weight_fraction = linked_unmeasured_weight_fraction;
    return options;
  }

  common::InlineExecutor executor_;
  PoseGraph2D graph_;
  const std::vector<test_world::Segment> walls_;
  std::unique_ptr<mapping::ActiveSubmaps2D> active_;
  sensor::AdaptiveVoxelFilterOptions filter_;
};

TEST(PoseGraph2DLoopsTest, NodeLinksSetACorridorsLengthWhereItsScansCannot) {
  constexpr int kNodes = 201;  // 20 m
  const double true_m = StretchedCorridorRun::kStepM * (kNodes - 1);

  StretchedCorridorRun without_links(1e-2);
  without_links.Drive(kNodes);
  without_links.graph().RunFinalOptimization();
  EXPECT_NEAR(without_links.FirstToLastM(), StretchedCorridorRun::kStretch * true_m, 0.02);

  StretchedCorridorRun linked(1e-2);
  linked.Drive(kNodes);
  EXPECT_EQ(linked.AddTrueLinks(kNodes, 8), (kNodes - 1) / 8);
  linked.graph().RunFinalOptimization();
  const PoseGraph2D::Stats stats = linked.graph().stats();
  EXPECT_EQ(stats.node_links, (kNodes - 1) / 8);
  // Every linked step's scan sees two parallel walls only.
  EXPECT_EQ(stats.linked_unmeasured_steps, 8 * ((kNodes - 1) / 8));
  std::printf("first to last node: true %.3f m, without links %.3f m, with %.3f m\n", true_m,
              without_links.FirstToLastM(), linked.FirstToLastM());
  // 60 cm of stretch, down to a centimetre.
  EXPECT_NEAR(linked.FirstToLastM(), true_m, 0.01);

  // Where local SLAM's steps keep their full weight, the links hardly move them: the weakening
  // is what lets the camera decide.
  StretchedCorridorRun full_weight(1.0);
  full_weight.Drive(kNodes);
  full_weight.AddTrueLinks(kNodes, 8);
  full_weight.graph().RunFinalOptimization();
  std::printf("with the steps at full weight %.3f m\n", full_weight.FirstToLastM());
  EXPECT_GT(full_weight.FirstToLastM() - true_m,
            0.5 * (StretchedCorridorRun::kStretch - 1.0) * true_m);
}

// Links the verifier trusts less (here a 2 cm standard error, 1e4) set the length all the same:
// a linked node's place in its submap, as odometry's along the corridor as its step, must not
// hold the stretch against them (it did: 20.21 m of 20 m).
TEST(PoseGraph2DLoopsTest, NodeLinksOfALessCertainCameraSetTheLengthToo) {
  constexpr int kNodes = 201;  // 20 m
  const double true_m = StretchedCorridorRun::kStepM * (kNodes - 1);
  StretchedCorridorRun linked(1e-2);
  linked.Drive(kNodes);
  EXPECT_EQ(linked.AddTrueLinks(kNodes, 8, 1e4), (kNodes - 1) / 8);
  linked.graph().RunFinalOptimization();
  std::printf("first to last node: true %.3f m, with links of weight 1e4 %.3f m\n", true_m,
              linked.FirstToLastM());
  EXPECT_NEAR(linked.FirstToLastM(), true_m, 0.01);
}

TEST(PoseGraph2DLoopsTest, NodeLinksLeaveStepsWhoseScansPinThemAlone) {
  // A closed room: every scan sees walls across both directions.
  std::vector<test_world::Segment> room;
  test_world::AddBox(-1.0, -1.5, 6.0, 1.5, &room);
  StretchedCorridorRun run(1e-2, room);
  run.Drive(41);
  EXPECT_EQ(run.AddTrueLinks(41, 8), 5);
  EXPECT_EQ(run.graph().stats().node_links, 5);
  EXPECT_EQ(run.graph().stats().linked_unmeasured_steps, 0);
}

TEST(PoseGraph2DLoopsTest, NodeLinksSurviveExportAndRestore) {
  constexpr int kNodes = 81;
  StretchedCorridorRun run(1e-2);
  run.Drive(kNodes);
  run.AddTrueLinks(kNodes, 8);
  std::vector<std::shared_ptr<const mapping::Submap2D>> submaps;
  const PoseGraphState2D state = run.graph().ExportState(&submaps);
  EXPECT_EQ(state.node_links.size(), 10u);

  common::InlineExecutor executor;
  PoseGraph2D restored(TestOptions(/*laser_loops=*/false), &executor);
  restored.RestoreState(state, submaps);
  EXPECT_EQ(restored.stats().node_links, 10);
  // Which steps the links cover, and that their scans pin nothing along, is worked out again.
  EXPECT_EQ(restored.stats().linked_unmeasured_steps, 80);
  restored.RunFinalOptimization();
  run.graph().RunFinalOptimization();
  const auto a = run.graph().Snapshot();
  const auto b = restored.Snapshot();
  EXPECT_NEAR((b->T_map_nodes.back().translation() - b->T_map_nodes.front().translation()).norm(),
              (a->T_map_nodes.back().translation() - a->T_map_nodes.front().translation()).norm(),
              1e-6);
}

TEST(PoseGraph2DLoopsTest, RefusesNodeLinksBackwardsOrToUnknownNodes) {
  StretchedCorridorRun run(1e-2);
  run.Drive(10);
  NodeLink2D link;
  link.from = 5;
  link.to = 5;
  EXPECT_FALSE(run.graph().AddNodeLink(link));
  link.from = 6;
  EXPECT_FALSE(run.graph().AddNodeLink(link));
  link.from = 2;
  link.to = 10;  // not added yet
  EXPECT_FALSE(run.graph().AddNodeLink(link));
  link.to = 9;
  EXPECT_TRUE(run.graph().AddNodeLink(link));
  EXPECT_EQ(run.graph().stats().node_links, 1);
}

}  // namespace
}  // namespace pose_graph
}  // namespace fusemap
