// PoseGraph2D's loop-constraint API (pose_graph_2d_loops.cc).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <set>
#include <vector>

#include "fusemap/common/math.h"
#include "fusemap/pose_graph/pose_graph_2d.h"
#include "fusemap/sensor/range_data_builder.h"
#include "fusemap/sensor/voxel_filter.h"
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
    const std::vector<test_world::Segment> walls = test_world::Room();
    mapping::SubmapsOptions submap_options;
    submap_options.num_range_data = 10;
    mapping::ActiveSubmaps2D active(submap_options);
    sensor::AdaptiveVoxelFilterOptions filter;
    filter.max_length_m = 0.9f;
    filter.min_num_points = 100;
    common::Rigid2d T_local_node = TruePose(0);
    for (int i = 0; i < num_nodes; ++i) {
      if (i > 0) {
        const common::Rigid2d delta = TruePose(i - 1).inverse() * TruePose(i);
        T_local_node = T_local_node * common::Rigid2d(1.01 * delta.translation(),
                                                      delta.angle_rad() + common::DegToRad(0.1));
      }
      const sensor::RangeData data = test_world::SimulateRangeData(walls, TruePose(i));
      const auto submaps = active.InsertRangeData(sensor::TransformRangeData(data, T_local_node));
      if (i == 0) first_submap_ = submaps.front();
      graph_.AddNode(0.1 * i, T_local_node, sensor::AdaptiveVoxelFilter(data.returns, filter),
                     submaps);
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
  common::Rigid2d TrueSubmap0Node(int node) const {
    return first_submap_->T_local_submap().inverse() * TruePose(node);
  }

  PoseGraph2D& graph() { return graph_; }

 private:
  common::InlineExecutor executor_;
  PoseGraph2D graph_;
  std::shared_ptr<const mapping::Submap2D> first_submap_;
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

}  // namespace
}  // namespace pose_graph
}  // namespace fusemap
