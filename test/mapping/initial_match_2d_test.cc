#include "fusemap/mapping/scan_matching/initial_match_2d.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "fusemap/mapping/probability_values.h"
#include "testing/synthetic_room.h"

namespace fusemap {
namespace mapping {
namespace {

ProbabilityGrid SmallGrid() {
  MapLimits limits;
  limits.resolution_m = 0.1;
  limits.origin_m = Eigen::Vector2d(1.0, -2.0);
  limits.num_x_cells = 5;
  limits.num_y_cells = 4;
  ProbabilityGrid grid(limits);
  grid.SetProbability(Eigen::Array2i(0, 0), 0.3f);
  grid.SetProbability(Eigen::Array2i(1, 1), 0.8f);  // same 2x2 block as (0, 0)
  grid.SetProbability(Eigen::Array2i(4, 3), 0.2f);  // alone in the last, partial block
  return grid;
}

TEST(MaxPoolGridTest, KeepsTheMostOccupiedKnownCellPerBlock) {
  const ProbabilityGrid coarse = MaxPoolGrid(SmallGrid(), 2, kMinProbability, 0);
  // Cropped to the known cells (0, 0)..(4, 3): 5 x 4 fine cells, 3 x 2 coarse ones.
  EXPECT_DOUBLE_EQ(coarse.limits().resolution_m, 0.2);
  EXPECT_EQ(coarse.limits().num_x_cells, 3);
  EXPECT_EQ(coarse.limits().num_y_cells, 2);
  EXPECT_NEAR(coarse.GetProbability(Eigen::Array2i(0, 0)), 0.8f, 1e-3);
  EXPECT_NEAR(coarse.GetProbability(Eigen::Array2i(2, 1)), 0.2f, 1e-3);
  EXPECT_FALSE(coarse.IsKnown(Eigen::Array2i(1, 0)));
  // Same world positions: the point at the centre of fine cell (1, 1) is in coarse cell (0, 0).
  EXPECT_TRUE((coarse.limits().GetCellIndex(Eigen::Vector2f(1.15f, -1.85f)) ==
               Eigen::Array2i(0, 0)).all());
}

TEST(MaxPoolGridTest, FillsUnknownAndPads) {
  const ProbabilityGrid coarse = MaxPoolGrid(SmallGrid(), 2, 0.5f, 3);
  EXPECT_EQ(coarse.limits().num_x_cells, 3 + 6);
  EXPECT_EQ(coarse.limits().num_y_cells, 2 + 6);
  EXPECT_NEAR(coarse.GetProbability(Eigen::Array2i(3, 3)), 0.8f, 1e-3);
  EXPECT_NEAR(coarse.GetProbability(Eigen::Array2i(4, 3)), 0.5f, 1e-3);  // was unknown
  EXPECT_NEAR(coarse.GetProbability(Eigen::Array2i(0, 0)), 0.5f, 1e-3);  // padding
  EXPECT_TRUE((coarse.limits().GetCellIndex(Eigen::Vector2f(1.15f, -1.85f)) ==
               Eigen::Array2i(3, 3)).all());
}

TEST(MaxPoolGridTest, FactorOneCopiesTheKnownCellsAndPads) {
  const ProbabilityGrid grid = SmallGrid();
  const ProbabilityGrid copy = MaxPoolGrid(grid, 1, 0.5f, 2);
  EXPECT_DOUBLE_EQ(copy.limits().resolution_m, 0.1);
  EXPECT_EQ(copy.limits().num_x_cells, 5 + 4);
  EXPECT_EQ(copy.limits().num_y_cells, 4 + 4);
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 5; ++x) {
      const Eigen::Array2i cell(x, y);
      const float expected = grid.IsKnown(cell) ? grid.GetProbability(cell) : 0.5f;
      EXPECT_NEAR(copy.GetProbability(cell + 2), expected, 1e-3) << x << " " << y;
    }
  }
  EXPECT_NEAR(copy.GetProbability(Eigen::Array2i(0, 0)), 0.5f, 1e-3);  // padding
}

// A submap of the synthetic room seen from `pose` (world frame = local frame).
std::shared_ptr<Submap2D> RoomSubmap(const common::Rigid2d& pose) {
  auto submap = std::make_shared<Submap2D>(pose.translation().cast<float>(), 0.05);
  const RangeDataInserter2D inserter{ProbabilityGridRangeDataInserterOptions()};
  for (int i = 0; i < 5; ++i) {
    submap->InsertRangeData(
        sensor::TransformRangeData(test_world::SimulateRangeData(test_world::Room(), pose), pose),
        inserter);
  }
  return submap;
}

TEST(InitialMatcher2DTest, FindsAPoseFarFromThePredictionAndCachesGrids) {
  const common::Rigid2d truth(3.0, 2.0, 0.3);
  const std::shared_ptr<const Submap2D> submap = RoomSubmap(truth);
  const sensor::PointCloud2d cloud =
      test_world::SimulateRangeData(test_world::Room(), truth).returns;
  InitialMatchOptions2D options;
  options.enabled = true;
  options.matching_resolution_m = 0.2;
  options.refresh_every_n_insertions = 3;
  // Wider than the default (local SLAM's window-edge search) and without its prior.
  options.fast_correlative_scan_matcher.linear_search_window_m = 2.0;
  options.fast_correlative_scan_matcher.angular_search_window_rad = common::DegToRad(30.0);
  options.fast_correlative_scan_matcher.translation_delta_cost_weight = 0.0;
  InitialMatcher2D matcher(options);
  double score = 0.0;
  common::Rigid2d pose;
  // 1.2 m and 0.4 rad off: far outside a real-time correlative window.
  ASSERT_TRUE(matcher.Match(submap, common::Rigid2d(4.0, 1.4, -0.1), cloud, &score, &pose));
  EXPECT_GT(score, 0.6);
  EXPECT_LT((pose.translation() - truth.translation()).norm(), 0.2);  // one search cell
  EXPECT_NEAR(pose.angle_rad(), truth.angle_rad(), 0.03);
  ASSERT_TRUE(matcher.Match(submap, common::Rigid2d(4.0, 1.4, -0.1), cloud, &score, &pose));
  EXPECT_EQ(matcher.num_precomputations(), 1);  // same submap and cells, no new insertions

  // The grids cover the cells a search reads only: a search 1.2 m away reads others, rebuilds
  // them, and answers as a matcher that never searched before.
  double fresh_score = 0.0;
  common::Rigid2d fresh_pose;
  ASSERT_TRUE(InitialMatcher2D(options).Match(submap, truth, cloud, &fresh_score, &fresh_pose));
  ASSERT_TRUE(matcher.Match(submap, truth, cloud, &score, &pose));
  EXPECT_EQ(matcher.num_precomputations(), 2);
  EXPECT_EQ(score, fresh_score);
  EXPECT_TRUE(pose.translation() == fresh_pose.translation());
  EXPECT_EQ(pose.angle_rad(), fresh_pose.angle_rad());

  // Another submap always rebuilds.
  ASSERT_TRUE(matcher.Match(RoomSubmap(truth), truth, cloud, &score, &pose));
  EXPECT_EQ(matcher.num_precomputations(), 3);
}

// min_fit leaves the answer as it was when the answer beats it, and leaves none otherwise.
TEST(InitialMatcher2DTest, MinFitKeepsTheAnswerOrFindsNone) {
  const common::Rigid2d truth(3.0, 2.0, 0.3);
  const std::shared_ptr<const Submap2D> submap = RoomSubmap(truth);
  const sensor::PointCloud2d cloud =
      test_world::SimulateRangeData(test_world::Room(), truth).returns;
  InitialMatchOptions2D options;  // local SLAM's window-edge search, with its prior
  options.enabled = true;
  InitialMatcher2D matcher(options);
  const common::Rigid2d predicted(3.3, 1.8, 0.45);
  double score = 0.0;
  common::Rigid2d pose;
  ASSERT_TRUE(matcher.Match(submap, predicted, cloud, &score, &pose));
  EXPECT_LT((pose.translation() - truth.translation()).norm(), 0.1);
  double score_with_min_fit = 0.0;
  common::Rigid2d pose_with_min_fit;
  ASSERT_TRUE(matcher.Match(submap, predicted, cloud, &score_with_min_fit, &pose_with_min_fit,
                            score - 1e-6));
  EXPECT_EQ(score_with_min_fit, score);
  EXPECT_TRUE(pose_with_min_fit.translation() == pose.translation());
  EXPECT_EQ(pose_with_min_fit.angle_rad(), pose.angle_rad());
  EXPECT_FALSE(matcher.Match(submap, predicted, cloud, &score_with_min_fit, &pose_with_min_fit,
                             score + 1e-6));
}

}  // namespace
}  // namespace mapping
}  // namespace fusemap
