#include "fusemap/visual_loop/loop_arbiter.h"

#include <gtest/gtest.h>

#include <string>

namespace fusemap {
namespace visual_loop {
namespace {

LoopMeasurement2D Measurement(double x, double y, double yaw) {
  LoopMeasurement2D m;
  m.T_submap_node = common::Rigid2d(x, y, yaw);
  return m;
}

struct Row {
  std::optional<LoopMeasurement2D> laser;
  std::optional<LoopMeasurement2D> visual;
  VisualCheck check;
  LoopSource source;
  LoopDecision decision;
  bool has_chosen;
  bool chosen_is_visual;
};

TEST(LoopArbiterTest, DecisionTable) {
  const auto laser = Measurement(2.0, 1.0, 0.5);
  const auto visual_close = Measurement(2.1, 1.05, 0.52);   // 0.11 m, 1.1 deg off
  const auto visual_far = Measurement(2.9, 1.0, 0.5);       // 0.9 m off
  const auto visual_turned = Measurement(2.0, 1.0, 0.75);   // 14 deg off
  const Row rows[] = {
      {laser, visual_close, VisualCheck::kVerified, LoopSource::kBoth, LoopDecision::kLaserConfirmed, true, false},
      {laser, visual_far, VisualCheck::kVerified, LoopSource::kBoth, LoopDecision::kVisualOverride, true, true},
      {laser, visual_turned, VisualCheck::kVerified, LoopSource::kBoth, LoopDecision::kVisualOverride, true, true},
      {std::nullopt, visual_far, VisualCheck::kVerified, LoopSource::kVisual, LoopDecision::kVisualForced, true, true},
      {laser, std::nullopt, VisualCheck::kNotChecked, LoopSource::kLaser, LoopDecision::kLaserKept, true, false},
      {laser, std::nullopt, VisualCheck::kContradicted, LoopSource::kLaser, LoopDecision::kLaserRejected, false, false},
  };
  for (size_t i = 0; i < std::size(rows); ++i) {
    const Row& row = rows[i];
    const ArbitrationRecord record = ArbitrateLoop(7, 3, row.laser, row.visual, row.check, ArbitrationOptions{});
    SCOPED_TRACE("row " + std::to_string(i) + ": " + record.reason);
    EXPECT_EQ(record.node, 7);
    EXPECT_EQ(record.submap, 3);
    EXPECT_EQ(record.source, row.source);
    EXPECT_EQ(record.decision, row.decision);
    EXPECT_FALSE(record.reason.empty());
    ASSERT_EQ(record.chosen.has_value(), row.has_chosen);
    // Both measurements are kept as evidence, whichever is chosen.
    EXPECT_EQ(record.laser.has_value(), row.laser.has_value());
    EXPECT_EQ(record.visual.has_value(), row.visual.has_value());
    if (record.chosen) {
      const auto& expected = row.chosen_is_visual ? *row.visual : *row.laser;
      EXPECT_EQ(record.chosen->T_submap_node.translation(), expected.T_submap_node.translation());
      EXPECT_EQ(record.chosen->T_submap_node.angle_rad(), expected.T_submap_node.angle_rad());
    }
  }
}

TEST(LoopArbiterTest, DisagreementIsMeasuredInTheNodeFrame) {
  const ArbitrationRecord record = ArbitrateLoop(1, 1, Measurement(0.0, 0.0, M_PI / 2),
                                                 Measurement(0.0, 0.2, M_PI / 2),
                                                 VisualCheck::kVerified, ArbitrationOptions{});
  EXPECT_NEAR(record.translation_disagreement_m, 0.2, 1e-12);
  EXPECT_NEAR(record.rotation_disagreement_rad, 0.0, 1e-12);
  EXPECT_STREQ(ToString(record.decision), "laser_confirmed");
  EXPECT_STREQ(ToString(record.source), "both");
}

// The same poster hung twice, 18 m apart along the robot's 40 m path: the visual loop asks the
// graph to move the node 18 m, where drift over 40 m explains 1 + 0.1 * 40 = 5 m. The same
// place on the next lap, 90 m of path later, asks 0.3 m: forced.
TEST(LoopArbiterTest, AVisualLoopDriftCannotExplainIsNotForced) {
  const ArbitrationOptions options;
  const GraphEstimate2D estimate{common::Rigid2d(2.0, 1.0, 0.5), 40.0};
  const ArbitrationRecord trap = ArbitrateLoop(9, 2, std::nullopt, Measurement(20.0, 1.0, 0.5),
                                               VisualCheck::kVerified, options, estimate);
  EXPECT_EQ(trap.decision, LoopDecision::kVisualRejected);
  EXPECT_STREQ(ToString(trap.decision), "visual_rejected");
  EXPECT_EQ(trap.source, LoopSource::kVisual);
  EXPECT_FALSE(trap.chosen.has_value());
  EXPECT_TRUE(trap.visual.has_value());
  EXPECT_NE(trap.reason.find("18.00 m"), std::string::npos) << trap.reason;

  // Seen the other way round: the same wall, turned by pi.
  const ArbitrationRecord turned =
      ArbitrateLoop(9, 2, std::nullopt, Measurement(2.0, 1.0, 0.5 + M_PI), VisualCheck::kVerified,
                    options, estimate);
  EXPECT_EQ(turned.decision, LoopDecision::kVisualRejected);

  const ArbitrationRecord next_lap =
      ArbitrateLoop(9, 2, std::nullopt, Measurement(2.3, 1.0, 0.52), VisualCheck::kVerified,
                    options, GraphEstimate2D{common::Rigid2d(2.0, 1.0, 0.5), 90.0});
  EXPECT_EQ(next_lap.decision, LoopDecision::kVisualForced);
  ASSERT_TRUE(next_lap.chosen.has_value());

  // The bound grows with the path: 18 m after 200 m of path is drift.
  const ArbitrationRecord long_way = ArbitrateLoop(
      9, 2, std::nullopt, Measurement(20.0, 1.0, 0.5), VisualCheck::kVerified, options,
      GraphEstimate2D{common::Rigid2d(2.0, 1.0, 0.5), 200.0});
  EXPECT_EQ(long_way.decision, LoopDecision::kVisualForced);
}

TEST(LoopArbiterTest, AVisualPoseNoBetterThanTheLasersDoesNotReplaceIt) {
  // The rooms world's east end, seen along a wall far off: the camera's pose said 0.39 m and
  // 5.7 deg off the laser's with 45 inliers, and the laser's pose explained 50 of its matches.
  const ArbitrationOptions options;
  const LoopMeasurement2D laser = Measurement(2.0, 1.0, 0.5);
  LoopMeasurement2D visual = Measurement(2.07, 0.61, 0.6);
  visual.visual_inliers = 45;
  visual.visual_matches_explained_by_laser = 50;
  EXPECT_TRUE(LaserAndVisualDisagree(laser, visual, options));  // the session counts only then
  const ArbitrationRecord kept =
      ArbitrateLoop(9, 2, laser, visual, VisualCheck::kVerified, options);
  EXPECT_EQ(kept.decision, LoopDecision::kLaserKept);
  EXPECT_EQ(kept.source, LoopSource::kBoth);
  ASSERT_TRUE(kept.chosen.has_value());
  EXPECT_EQ(kept.chosen->T_submap_node.translation(), laser.T_submap_node.translation());
  EXPECT_TRUE(kept.visual.has_value());  // still recorded as evidence
  EXPECT_NE(kept.reason.find("explains 50 of the camera's matches against its own 45"),
            std::string::npos)
      << kept.reason;

  // Where the laser's pose explains few of them, the camera's replaces it.
  visual.visual_matches_explained_by_laser = 22;  // not more than half of 45
  EXPECT_EQ(ArbitrateLoop(9, 2, laser, visual, VisualCheck::kVerified, options).decision,
            LoopDecision::kVisualOverride);
  // Not counted: the thresholds alone decide, as before.
  visual.visual_matches_explained_by_laser = -1;
  EXPECT_EQ(ArbitrateLoop(9, 2, laser, visual, VisualCheck::kVerified, options).decision,
            LoopDecision::kVisualOverride);
  // Where they agree the count does not matter.
  LoopMeasurement2D close = Measurement(2.05, 1.0, 0.51);
  close.visual_inliers = 45;
  close.visual_matches_explained_by_laser = 5;
  EXPECT_FALSE(LaserAndVisualDisagree(laser, close, options));
  EXPECT_EQ(ArbitrateLoop(9, 2, laser, close, VisualCheck::kVerified, options).decision,
            LoopDecision::kLaserConfirmed);
}

}  // namespace
}  // namespace visual_loop
}  // namespace fusemap
