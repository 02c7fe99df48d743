#include "fusemap/eval/loop_closure_score.h"

#include <gtest/gtest.h>

#include <cmath>

#include "fusemap/common/math.h"

namespace fusemap {
namespace eval {
namespace {

Trajectory FromPoses(const std::vector<common::Rigid2d>& poses) {
  Trajectory trajectory;
  for (size_t i = 0; i < poses.size(); ++i) {
    trajectory.push_back({static_cast<double>(i), common::Rigid3d::FromRigid2d(poses[i])});
  }
  return trajectory;
}

TEST(StartEndErrorTest, ComparesFirstToLastMotionWithTruth) {
  // Truth returns to the start; the estimate ends 0.6 m and 2 deg off in its own frame.
  const Trajectory gt = FromPoses({{0, 0, 0}, {5, 0, 1.0}, {0, 0, 0}});
  const Trajectory est = FromPoses({{1, 1, 0.5}, {6, 1, 1.5}, common::Rigid2d(1, 1, 0.5) *
                                                             common::Rigid2d(0.6, 0, common::DegToRad(2))});
  StartEndError result;
  std::string error;
  ASSERT_TRUE(ComputeStartEndError(gt, est, 0.05, &result, &error)) << error;
  EXPECT_NEAR(result.translation_m, 0.6, 1e-9);
  EXPECT_NEAR(result.rotation_deg, 2.0, 1e-9);
  EXPECT_FALSE(ComputeStartEndError(gt, Trajectory(), 0.05, &result, &error));
}

TEST(ScoreLoopsTest, FlagsLoopsOffTheTruthAndCountsDecisions) {
  // Truth: node 0 at the origin, node 1 at (10, 0), node 2 at (10, 2) facing +y.
  const Trajectory gt = FromPoses({{0, 0, 0}, {10, 0, 0}, {10, 2, common::kPi / 2}});
  // The estimate is drifted and rotated as a whole: loops are relative, so that must not count.
  const common::Rigid2d drift(3, -1, 0.3);
  const Trajectory nodes = FromPoses({drift * common::Rigid2d(0, 0, 0),
                                      drift * common::Rigid2d(10, 0, 0),
                                      drift * common::Rigid2d(10, 2, common::kPi / 2)});
  // Submap 0 starts at node 0; its frame is rotated by 0.1 rad against node 0 (local yaw).
  const common::Rigid2d T_map_submap0 = drift * common::Rigid2d(0, 0, -0.1);
  std::vector<SubmapAnchor> submaps = {{0, 0, T_map_submap0}};
  const common::Rigid2d T_submap_node2 = common::Rigid2d(0, 0, 0.1) * common::Rigid2d(10, 2, common::kPi / 2);
  std::vector<LoopRecord> loops(4);
  loops[0] = {2, 0, "laser", 0.7, 0, "laser_kept", T_submap_node2};
  loops[1] = {2, 0, "laser", 0.6, 0, "laser_kept", T_submap_node2 * common::Rigid2d(0.5, 0, 0)};
  loops[2] = {2, 0, "visual", 0.0, 80, "laser_rejected", T_submap_node2 * common::Rigid2d(0, 0, 0.1)};
  loops[3] = {2, 7, "visual", 0.0, 80, "visual_forced", T_submap_node2};  // unknown submap
  const LoopScore score = ScoreLoops(loops, submaps, nodes, gt, LoopScoreOptions());
  ASSERT_EQ(score.loops.size(), 4u);
  EXPECT_TRUE(score.loops[0].scored);
  EXPECT_NEAR(score.loops[0].translation_error_m, 0.0, 1e-9);
  EXPECT_FALSE(score.loops[0].wrong);
  EXPECT_NEAR(score.loops[1].translation_error_m, 0.5, 1e-9);
  EXPECT_TRUE(score.loops[1].wrong);
  EXPECT_NEAR(score.loops[2].rotation_error_deg, 0.1 * 180.0 / common::kPi, 1e-6);
  EXPECT_TRUE(score.loops[2].wrong);
  EXPECT_FALSE(score.loops[2].accepted);
  EXPECT_FALSE(score.loops[3].scored);
  EXPECT_EQ(score.accepted, 3);
  EXPECT_EQ(score.wrong_accepted, 1);
  EXPECT_EQ(score.wrong_rejected, 1);
  EXPECT_EQ(score.unscored, 1);
  EXPECT_EQ(score.by_decision.at("laser_kept"), 2);
  EXPECT_EQ(score.by_decision.at("laser_rejected"), 1);
  EXPECT_EQ(score.by_decision.at("visual_forced"), 1);
  EXPECT_EQ(score.wrong_by_decision.at("laser_kept"), 1);
  EXPECT_EQ(score.wrong_by_decision.at("laser_rejected"), 1);
  EXPECT_EQ(score.wrong_by_decision.count("visual_forced"), 0u);  // unscored
}

TEST(ScoreLoopsTest, ALoopHeldAcrossACorridorIsScoredAcrossIt) {
  // Node 1 stands 10 m along a corridor (x) from node 0, which starts submap 0.
  const Trajectory gt = FromPoses({{0, 0, 0}, {10, 0, 0}});
  const Trajectory nodes = gt;
  std::vector<SubmapAnchor> submaps = {{0, 0, common::Rigid2d::Identity()}};
  // Both loops put node 1 0.5 m too far along x; the first measured only across (y).
  std::vector<LoopRecord> loops(3);
  loops[0] = {1, 0, "laser", 0.7, 0, "laser_kept", common::Rigid2d(10.5, 0.0, 0.0)};
  loops[0].unmeasured_direction = Eigen::Vector2d(1.0, 0.0);
  loops[1] = {1, 0, "laser", 0.7, 0, "laser_kept", common::Rigid2d(10.5, 0.0, 0.0)};
  // Held across only, but off across it: wrong.
  loops[2] = {1, 0, "laser", 0.7, 0, "laser_kept", common::Rigid2d(10.5, 0.4, 0.0)};
  loops[2].unmeasured_direction = Eigen::Vector2d(-1.0, 0.0);
  const LoopScore score = ScoreLoops(loops, submaps, nodes, gt, LoopScoreOptions());
  ASSERT_EQ(score.loops.size(), 3u);
  EXPECT_NEAR(score.loops[0].translation_error_m, 0.0, 1e-9);
  EXPECT_FALSE(score.loops[0].wrong);
  EXPECT_NEAR(score.loops[1].translation_error_m, 0.5, 1e-9);
  EXPECT_TRUE(score.loops[1].wrong);
  EXPECT_NEAR(score.loops[2].translation_error_m, 0.4, 1e-9);
  EXPECT_TRUE(score.loops[2].wrong);
  EXPECT_EQ(score.held_across_only, 2);
  EXPECT_EQ(score.wrong_accepted, 2);
}

TEST(ScoreLoopsTest, ALoopHeldAcrossARingCorridorIsScoredWithTheTurnThatGoesWithIt) {
  // Node 1 faces along a ring corridor of radius 10 m; the loops put it 0.5 m further round
  // (forward = the node's x axis), where the ring has turned 0.05 rad.
  const Trajectory gt = FromPoses({{0, 0, 0}, {10, 0, 0.5 * common::kPi}});
  std::vector<SubmapAnchor> submaps = {{0, 0, common::Rigid2d::Identity()}};
  const common::Rigid2d further_round =
      common::Rigid2d(10.0 * std::cos(0.05), 10.0 * std::sin(0.05), 0.5 * common::kPi + 0.05);
  std::vector<LoopRecord> loops(2);
  // Held across only, with the ring's turn: where it is round the ring is not its error.
  loops[0] = {1, 0, "laser", 0.7, 0, "laser_kept", further_round};
  loops[0].unmeasured_direction = Eigen::Vector2d(1.0, 0.0);
  loops[0].unmeasured_turn_rad_per_m = 0.1;
  // Held across a straight corridor: its heading is 2.9 degrees off.
  loops[1] = loops[0];
  loops[1].unmeasured_turn_rad_per_m = 0.0;
  const LoopScore score = ScoreLoops(loops, submaps, gt, gt, LoopScoreOptions());
  ASSERT_EQ(score.loops.size(), 2u);
  EXPECT_LT(score.loops[0].translation_error_m, 0.02);
  EXPECT_LT(score.loops[0].rotation_error_deg, 0.05);
  EXPECT_NEAR(score.loops[1].rotation_error_deg, 2.865, 0.01);
}

}  // namespace
}  // namespace eval
}  // namespace fusemap
