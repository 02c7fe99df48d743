#include "fusemap/pose_graph/loop_closure_matcher_2d.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <optional>
#include <vector>

#include "fusemap/common/math.h"
#include "testing/synthetic_room.h"
#include "fusemap/sensor/range_data_builder.h"
#include "fusemap/sensor/voxel_filter.h"

namespace fusemap {
namespace pose_graph {
namespace {

using test_world::Room;
using test_world::Segment;
using test_world::SimulateRangeData;

// A round room (24-gon of radius 3 m around the origin): nothing like the rectangular one.
std::vector<Segment> RoundRoom() {
  std::vector<Segment> walls;
  test_world::AddCircle(3.0, 24, &walls);
  return walls;
}

sensor::PointCloud2d LoopClosureCloud(const sensor::RangeData& range_data) {
  sensor::AdaptiveVoxelFilterOptions options;
  options.max_length_m = 0.9f;
  options.min_num_points = 100;
  return sensor::AdaptiveVoxelFilter(range_data.returns, options);
}

common::Rigid2d ArcPose(int i) { return test_world::ArcPose(i, 0.1); }

// A finished submap built from 20 scans of `walls` taken at pose(0..19), inserted at those
// true poses (so the local frame is the world frame).
std::shared_ptr<const mapping::Submap2D> BuildFinishedSubmap(
    const std::vector<Segment>& walls, const std::function<common::Rigid2d(int)>& pose) {
  mapping::SubmapsOptions options;
  options.num_range_data = 10;
  mapping::ActiveSubmaps2D active(options);
  std::shared_ptr<const mapping::Submap2D> front;
  for (int i = 0; i < 20; ++i) {
    const sensor::RangeData data = SimulateRangeData(walls, pose(i));
    front = active.InsertRangeData(sensor::TransformRangeData(data, pose(i))).front();
  }
  return front;
}

// ... along the arc around the room's island.
std::shared_ptr<const mapping::Submap2D> BuildFinishedSubmap() {
  return BuildFinishedSubmap(Room(), ArcPose);
}

TEST(LoopClosureMatcher2DTest, FindsTruePoseFromOffsetEstimate) {
  const auto submap = BuildFinishedSubmap();
  ASSERT_TRUE(submap->finished());
  const ConstraintBuilderOptions2D options;
  const LoopClosureMatcher2D matcher(submap, options);

  // A pose between the ones the submap was built from.
  const common::Rigid2d T_world_node(6.9, 1.75, 0.35);
  const common::Rigid2d T_submap_node = submap->T_local_submap().inverse() * T_world_node;
  const common::Rigid2d estimate(T_submap_node.translation() + Eigen::Vector2d(0.5, 0.0),
                                 T_submap_node.angle_rad() + common::DegToRad(5.0));
  double score = 0.0;
  const auto constraint =
      matcher.Match(estimate, LoopClosureCloud(SimulateRangeData(Room(), T_world_node)),
                    options.fast_correlative_scan_matcher.min_score, &score);
  ASSERT_TRUE(constraint.has_value()) << "score " << score;
  // The room holds the match every way.
  EXPECT_TRUE(constraint->unmeasured_direction.isZero());
  std::printf("score %.3f, error %.4f m %.4f deg\n", score,
              (constraint->T_submap_node.translation() - T_submap_node.translation()).norm(),
              common::NormalizeAngle(constraint->T_submap_node.angle_rad() -
                                     T_submap_node.angle_rad()) * 180.0 / common::kPi);
  EXPECT_GT(score, options.fast_correlative_scan_matcher.min_score);
  EXPECT_EQ(constraint->tag, Constraint2D::kInterSubmap);
  EXPECT_EQ(constraint->translation_weight, options.loop_closure_translation_weight);
  EXPECT_EQ(constraint->rotation_weight, options.loop_closure_rotation_weight);
  EXPECT_LT((constraint->T_submap_node.translation() - T_submap_node.translation()).norm(), 0.03);
  EXPECT_LT(std::abs(common::NormalizeAngle(constraint->T_submap_node.angle_rad() -
                                            T_submap_node.angle_rad())),
            common::DegToRad(0.5));
  // 0.5 m and 5 deg off, the scan fits the room far worse at the estimate than at the match.
  std::printf("evidence %.1f standard errors\n", constraint->evidence_z);
  EXPECT_GT(constraint->evidence_z, options.min_correction_evidence_z);
  EXPECT_TRUE(EvidenceSupportsCorrection(estimate, constraint->T_submap_node,
                                         constraint->evidence_z, options));
}

TEST(LoopClosureMatcher2DTest, AMatchPassesTheThresholdItIsGivenAndScoreAtAgrees) {
  const auto submap = BuildFinishedSubmap();
  const LoopClosureMatcher2D matcher(submap, ConstraintBuilderOptions2D{});
  const common::Rigid2d T_world_node(6.9, 1.75, 0.35);
  const common::Rigid2d T_submap_node = submap->T_local_submap().inverse() * T_world_node;
  const common::Rigid2d estimate(T_submap_node.translation() + Eigen::Vector2d(0.3, 0.0),
                                 T_submap_node.angle_rad());
  const sensor::PointCloud2d cloud = LoopClosureCloud(SimulateRangeData(Room(), T_world_node));
  double score = 0.0;
  ASSERT_TRUE(matcher.Match(estimate, cloud, 0.0, &score).has_value());
  double other = 0.0;
  EXPECT_FALSE(matcher.Match(estimate, cloud, score + 0.01, &other).has_value());
  EXPECT_TRUE(matcher.Match(estimate, cloud, score - 0.01, &other).has_value());
  // Scored where the scan was taken, without a search: about what the match scored (the search
  // ranks candidates with its prior on the estimate), far better than at the estimate.
  const double at_truth = matcher.ScoreAt(T_submap_node, cloud);
  EXPECT_NEAR(at_truth, score, 0.1);
  EXPECT_LT(matcher.ScoreAt(estimate, cloud), at_truth - 0.05);
}

TEST(MinScoreForOwnFitTest, LowersTheThresholdOnlyInSubmapsThatFitTheirOwnScansPoorly) {
  ConstraintBuilderOptions2D options;
  options.fast_correlative_scan_matcher.min_score = 0.55;
  options.min_score_of_own_fit = 0.85;
  EXPECT_DOUBLE_EQ(MinScoreForOwnFit(0.0, options), 0.55);  // not measured
  EXPECT_DOUBLE_EQ(MinScoreForOwnFit(0.70, options), 0.55);  // an office: 0.595 is above
  EXPECT_DOUBLE_EQ(MinScoreForOwnFit(0.56, options), 0.85 * 0.56);  // outdoors
  EXPECT_DOUBLE_EQ(MinScoreForOwnFit(0.48, options), 0.55);  // blurred
  options.min_score_of_own_fit = 0.0;
  EXPECT_DOUBLE_EQ(MinScoreForOwnFit(0.56, options), 0.55);
}

TEST(LoopClosureMatcher2DTest, RejectsScanFromDifferentRoom) {
  const auto submap = BuildFinishedSubmap();
  const ConstraintBuilderOptions2D options;
  const LoopClosureMatcher2D matcher(submap, options);
  const common::Rigid2d T_world_node(6.9, 1.75, 0.35);
  const common::Rigid2d estimate = submap->T_local_submap().inverse() * T_world_node;
  double score = 1.0;
  const auto constraint = matcher.Match(
      estimate, LoopClosureCloud(SimulateRangeData(RoundRoom(), common::Rigid2d(0.4, -0.2, 0.1))),
      options.fast_correlative_scan_matcher.min_score, &score);
  std::printf("different room: score %.3f\n", score);
  EXPECT_FALSE(constraint.has_value());
  EXPECT_LT(score, options.fast_correlative_scan_matcher.min_score);
}

// A 2 m wide corridor of plain walls, 60 m long along x: a scan in it (12 m of range) sees two
// parallel lines, which fit as well anywhere along it.
std::vector<Segment> Corridor() {
  return {{{-30.0, -1.0}, {30.0, -1.0}}, {{-30.0, 1.0}, {30.0, 1.0}}};
}

// ... 0.2 m apart along the corridor's axis.
std::shared_ptr<const mapping::Submap2D> BuildFinishedCorridorSubmap() {
  return BuildFinishedSubmap(Corridor(), [](int i) { return common::Rigid2d(0.2 * i, 0.0, 0.0); });
}

TEST(LoopClosureMatcher2DTest, ACorridorMatchHoldsTheNodeAcrossTheCorridorOnly) {
  const auto submap = BuildFinishedCorridorSubmap();
  ASSERT_TRUE(submap->finished());
  const common::Rigid2d T_world_node(2.0, 0.1, 0.05);
  const common::Rigid2d T_submap_node = submap->T_local_submap().inverse() * T_world_node;
  // 0.5 m off along the corridor, 0.2 m across it.
  const common::Rigid2d estimate =
      submap->T_local_submap().inverse() *
      common::Rigid2d(T_world_node.translation() + Eigen::Vector2d(0.5, 0.2), 0.05);
  const sensor::PointCloud2d cloud = LoopClosureCloud(SimulateRangeData(Corridor(), T_world_node));
  // The corridor's axis, in the submap frame.
  const Eigen::Vector2d axis =
      submap->T_local_submap().rotation().inverse() * Eigen::Vector2d::UnitX();

  ConstraintBuilderOptions2D every_way;
  every_way.min_translation_information_ratio = 0.0;
  double score = 0.0;
  const auto plain = LoopClosureMatcher2D(submap, every_way)
                         .Match(estimate, cloud, every_way.fast_correlative_scan_matcher.min_score,
                                &score);
  ASSERT_TRUE(plain.has_value());
  EXPECT_GT(score, every_way.fast_correlative_scan_matcher.min_score);
  EXPECT_TRUE(plain->unmeasured_direction.isZero());

  const ConstraintBuilderOptions2D defaults;
  EXPECT_GT(defaults.min_translation_information_ratio, 0.0);
  const auto held = LoopClosureMatcher2D(submap, defaults)
                        .Match(estimate, cloud, defaults.fast_correlative_scan_matcher.min_score,
                               &score);
  ASSERT_TRUE(held.has_value());
  // It measures nothing along the corridor (the node's frame is turned 0.05 rad from it)...
  EXPECT_NEAR(held->unmeasured_direction.norm(), 1.0, 1e-9);
  EXPECT_GT(std::abs(held->unmeasured_direction.dot(
                Eigen::Vector2d(std::cos(-0.05), std::sin(-0.05)))),
            0.99);
  // ... keeps the estimate there, and measures the rest.
  const Eigen::Vector2d off = held->T_submap_node.translation() - T_submap_node.translation();
  EXPECT_NEAR(off.dot(axis), 0.5, 0.01);
  EXPECT_LT(std::abs(off.dot(Eigen::Vector2d(-axis.y(), axis.x()))), 0.03);
  EXPECT_LT(std::abs(common::NormalizeAngle(held->T_submap_node.angle_rad() -
                                            T_submap_node.angle_rad())),
            common::DegToRad(0.5));
}

TEST(LoopClosureMatcher2DTest, ARingCorridorMatchTurnsAsItSlidesRoundTheRing) {
  // A ring corridor between radii 6 and 8 m: scans on the 7 m circle 0.21 m apart. Sliding a
  // match round the ring turns it, so a slide back to the estimate that kept the match's
  // heading would measure a heading off by the angle slid (here 4.1 degrees).
  const std::vector<Segment> ring = test_world::RingCorridorWalls(6.0, 8.0);
  const auto submap =
      BuildFinishedSubmap(ring, [](int i) { return test_world::RingPose(7.0, 0.2 + 0.03 * i); });
  ASSERT_TRUE(submap->finished());
  const common::Rigid2d T_world_node = test_world::RingPose(7.0, 0.45);
  // 0.5 m further round the ring, 0.1 m out from the centre.
  const double estimate_angle_rad = 0.45 + 0.5 / 7.0;
  const common::Rigid2d estimate =
      submap->T_local_submap().inverse() * test_world::RingPose(7.1, estimate_angle_rad);
  const ConstraintBuilderOptions2D defaults;
  double score = 0.0;
  const auto held = LoopClosureMatcher2D(submap, defaults)
                        .Match(estimate, LoopClosureCloud(SimulateRangeData(ring, T_world_node)),
                               defaults.fast_correlative_scan_matcher.min_score, &score);
  ASSERT_TRUE(held.has_value());
  // It measures nothing round the ring (the node's x axis), turning 1/7 rad a metre forward...
  EXPECT_GT(std::abs(held->unmeasured_direction.x()), 0.99);
  EXPECT_NEAR(held->unmeasured_turn_rad_per_m * held->unmeasured_direction.x(), 1.0 / 7.0, 0.02);
  // ... keeps the estimate round the ring, with the heading the ring has there, and measures
  // the distance from the centre.
  const common::Rigid2d expected =
      submap->T_local_submap().inverse() * test_world::RingPose(7.0, estimate_angle_rad);
  EXPECT_LT((held->T_submap_node.translation() - expected.translation()).norm(), 0.05);
  EXPECT_LT(
      std::abs(common::NormalizeAngle(held->T_submap_node.angle_rad() - expected.angle_rad())),
      common::DegToRad(0.5));
}

TEST(LoopClosureMatcher2DTest, EmptyCloudIsRejected) {
  const auto submap = BuildFinishedSubmap();
  const ConstraintBuilderOptions2D options;
  const LoopClosureMatcher2D matcher(submap, options);
  double score = 1.0;
  EXPECT_FALSE(
      matcher.Match(common::Rigid2d(), {}, options.fast_correlative_scan_matcher.min_score, &score)
          .has_value());
  EXPECT_EQ(score, 0.0);
}

// A match moving the node 3 m from the estimate: drift does not explain it after 25 m of travel
// (bound 0.5 m + 0.02 x 25 m), it does after 150 m (3.5 m); with max_correction_m 0 anything goes.
TEST(DriftExplainsCorrectionTest, TheBoundGrowsWithThePathBetween) {
  ConstraintBuilderOptions2D options;
  ASSERT_EQ(options.max_correction_m, 0.5);
  ASSERT_EQ(options.max_correction_per_path_m, 0.02);
  const common::Rigid2d estimate(Eigen::Vector2d(2.0, 1.0), 0.3);
  const common::Rigid2d three_m_off(Eigen::Vector2d(2.0, 4.0), 0.3);
  EXPECT_TRUE(DriftExplainsCorrection(estimate, estimate, 0.0, options));
  EXPECT_FALSE(DriftExplainsCorrection(estimate, three_m_off, 25.0, options));
  EXPECT_TRUE(DriftExplainsCorrection(estimate, three_m_off, 150.0, options));
  // Only translation: the angular search window already bounds the turn.
  const common::Rigid2d turned(Eigen::Vector2d(2.0, 1.0), 0.6);
  EXPECT_TRUE(DriftExplainsCorrection(estimate, turned, 0.0, options));
  options.max_correction_m = 0.0;
  EXPECT_TRUE(DriftExplainsCorrection(estimate, three_m_off, 0.0, options));
}

// The linear window follows the drift bound: 4 m (the configured window) until the bound
// passes it at 175 m of path, 6.5 m after 300 m, never more than 12 m; fixed without the bound.
TEST(LoopSearchWindowMTest, FollowsTheDriftBoundWithinItsLimits) {
  ConstraintBuilderOptions2D options;
  ASSERT_EQ(options.fast_correlative_scan_matcher.linear_search_window_m, 4.0);
  ASSERT_EQ(options.max_linear_search_window_m, 12.0);
  EXPECT_DOUBLE_EQ(LoopSearchWindowM(0.0, options), 4.0);
  EXPECT_DOUBLE_EQ(LoopSearchWindowM(100.0, options), 4.0);
  EXPECT_DOUBLE_EQ(LoopSearchWindowM(300.0, options), 6.5);
  EXPECT_DOUBLE_EQ(LoopSearchWindowM(2000.0, options), 12.0);
  options.max_correction_m = 0.0;
  EXPECT_DOUBLE_EQ(LoopSearchWindowM(2000.0, options), 4.0);
}

// A revisit whose estimate is 5.1 m off, beyond the fixed 4 m window: not found right just
// after the submap, found within centimetres after 300 m of path (window 6.5 m).
TEST(LoopClosureMatcher2DTest, ARevisitBeyondTheFixedWindowIsFoundAfterALongPath) {
  const auto submap = BuildFinishedSubmap();
  const ConstraintBuilderOptions2D options;
  const LoopClosureMatcher2D matcher(submap, options);
  const common::Rigid2d T_world_node(6.9, 1.75, 0.35);
  const common::Rigid2d T_submap_node = submap->T_local_submap().inverse() * T_world_node;
  const common::Rigid2d estimate(T_submap_node.translation() + Eigen::Vector2d(-5.0, 1.0),
                                 T_submap_node.angle_rad());
  const sensor::PointCloud2d cloud = LoopClosureCloud(SimulateRangeData(Room(), T_world_node));
  const double min_score = options.fast_correlative_scan_matcher.min_score;
  const auto error_m = [&](const std::optional<Constraint2D>& c) {
    return c ? (c->T_submap_node.translation() - T_submap_node.translation()).norm()
             : std::numeric_limits<double>::infinity();
  };
  double score = 0.0;
  EXPECT_GT(error_m(matcher.Match(estimate, cloud, min_score, &score, 0.0)), 0.5);
  const auto after_long_path = matcher.Match(estimate, cloud, min_score, &score, 300.0);
  ASSERT_TRUE(after_long_path.has_value()) << "score " << score;
  EXPECT_LT(error_m(after_long_path), 0.03);
  EXPECT_TRUE(DriftExplainsCorrection(estimate, after_long_path->T_submap_node, 300.0, options));
}

// Up to 0.2 m a match is taken on its score; beyond, only with 2 standard errors of evidence
// over the estimate; min_correction_evidence_z 0 takes every match.
TEST(EvidenceSupportsCorrectionTest, LargerCorrectionsNeedEvidence) {
  ConstraintBuilderOptions2D options;
  ASSERT_EQ(options.max_unevidenced_correction_m, 0.2);
  ASSERT_EQ(options.min_correction_evidence_z, 2.0);
  const common::Rigid2d estimate(Eigen::Vector2d(2.0, 1.0), 0.3);
  const common::Rigid2d near(Eigen::Vector2d(2.15, 1.0), 0.3);
  const common::Rigid2d room_away(Eigen::Vector2d(2.0, 1.4), 0.3);
  EXPECT_TRUE(EvidenceSupportsCorrection(estimate, near, 0.0, options));
  EXPECT_FALSE(EvidenceSupportsCorrection(estimate, room_away, 0.9, options));
  EXPECT_TRUE(EvidenceSupportsCorrection(estimate, room_away, 2.5, options));
  options.min_correction_evidence_z = 0.0;
  EXPECT_TRUE(EvidenceSupportsCorrection(estimate, room_away, 0.0, options));
}

TEST(FixedRatioSamplerTest, PassesExpectedFraction) {
  for (const double ratio : {0.0, 0.1, 0.3, 0.5, 1.0}) {
    FixedRatioSampler sampler(ratio);
    int passed = 0;
    for (int n = 1; n <= 1000; ++n) {
      if (sampler.Pulse()) ++passed;
      // The fewest samples that keep passed / n >= ratio.
      const int expected = static_cast<int>(std::ceil(ratio * n - 1e-9));
      ASSERT_EQ(passed, expected) << "ratio " << ratio << " after " << n << " pulses";
    }
  }
}

TEST(ConstraintBuilderOptions2DTest, RejectsBadOptions) {
  std::string error;
  ConstraintBuilderOptions2D options;
  EXPECT_TRUE(options.IsValid(&error)) << error;
  options.sampling_ratio = 1.5;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("sampling_ratio"), std::string::npos);
  options.sampling_ratio = 0.3;
  options.max_constraint_distance_m = 0.0;
  EXPECT_FALSE(options.IsValid(&error));
  options.max_constraint_distance_m = 15.0;
  options.max_correction_per_path_m = -0.1;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("max_correction_per_path_m"), std::string::npos) << error;
  options.max_correction_per_path_m = 0.02;
  options.min_correction_evidence_z = -1.0;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("min_correction_evidence_z"), std::string::npos) << error;
  options.min_correction_evidence_z = 2.0;
  options.max_unevidenced_correction_m = -0.1;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("max_unevidenced_correction_m"), std::string::npos) << error;
  options.max_unevidenced_correction_m = 0.2;
  options.min_score_of_own_fit = 1.5;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("min_score_of_own_fit"), std::string::npos) << error;
  options.min_score_of_own_fit = 0.85;
  options.max_linear_search_window_m = 3.0;  // below the 4 m window
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("max_linear_search_window_m"), std::string::npos) << error;
}

}  // namespace
}  // namespace pose_graph
}  // namespace fusemap
