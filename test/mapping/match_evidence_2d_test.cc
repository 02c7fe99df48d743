#include "fusemap/mapping/scan_matching/match_evidence_2d.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "testing/wall_grid.h"

namespace fusemap {
namespace mapping {
namespace {

using test_world::Segment;

// A 2 m wide corridor, 10 m long along x, drawn on a 5 cm grid; walls only, so a scan inside
// it slides along x at no cost.
std::vector<Segment> CorridorWalls() {
  return {{Eigen::Vector2d(-5.0, -1.025), Eigen::Vector2d(5.0, -1.025)},
          {Eigen::Vector2d(-5.0, 0.975), Eigen::Vector2d(5.0, 0.975)}};
}

ProbabilityGrid CorridorGrid() {
  MapLimits limits;
  limits.resolution_m = 0.05;
  limits.origin_m = Eigen::Vector2d(-6.0, -2.0);
  limits.num_x_cells = 240;
  limits.num_y_cells = 80;
  return test_world::DrawWalls(limits, CorridorWalls());
}

TEST(MatchEvidence2DTest, AMatchAcrossTheWallsIsEvidencedOneAlongThemIsNot) {
  const ProbabilityGrid grid = CorridorGrid();
  const common::Rigid2d truth(0.0, 0.0, 0.0);
  // The scan's walls, 4 m each way (the corridor's ends out of range).
  const sensor::PointCloud2d cloud = test_world::CastCloud(CorridorWalls(), truth, 360, 4.0);
  ASSERT_GT(cloud.size(), 100u);
  // 0.3 m across the corridor: every point off its wall.
  const double across = GainInStandardErrors(grid, kMinProbability,
                                             common::Rigid2d(0.0, 0.3, 0.0), truth, cloud);
  EXPECT_GT(across, 10.0);
  // 0.5 m along it: every point still on a wall, as good a fit as the truth.
  const double along = GainInStandardErrors(grid, kMinProbability,
                                            common::Rigid2d(0.5, 0.0, 0.0), truth, cloud);
  EXPECT_LT(along, 1.0);
}

TEST(MatchEvidence2DTest, AWorseCandidateOrNoCloudGainsNothing) {
  const ProbabilityGrid grid = CorridorGrid();
  const common::Rigid2d truth(0.0, 0.0, 0.0);
  const sensor::PointCloud2d cloud = test_world::CastCloud(CorridorWalls(), truth, 360, 4.0);
  EXPECT_EQ(GainInStandardErrors(grid, kMinProbability, truth, common::Rigid2d(0.0, 0.3, 0.0),
                                 cloud),
            0.0);
  EXPECT_EQ(GainInStandardErrors(grid, kMinProbability, common::Rigid2d(0.0, 0.3, 0.0), truth,
                                 sensor::PointCloud2d{}),
            0.0);
}

TEST(MatchEvidence2DTest, NeverObservedCellsReadAsTheGivenProbability) {
  // An empty grid: every cell unknown. One point, moved off the grid: both read the same.
  MapLimits limits;
  limits.resolution_m = 0.05;
  limits.num_x_cells = 10;
  limits.num_y_cells = 10;
  ProbabilityGrid grid(limits);
  grid.SetProbability(Eigen::Array2i(2, 2), 0.9f);
  const sensor::PointCloud2d cloud = {Eigen::Vector2f(0.0f, 0.0f)};
  const common::Rigid2d on_the_known_cell(limits.GetCellCenter(Eigen::Array2i(2, 2)), 0.0);
  const common::Rigid2d off_the_grid(-10.0, -10.0, 0.0);
  // One point gaining 0.9 - unknown: the same gain for every point, so no spread.
  EXPECT_EQ(GainInStandardErrors(grid, 0.5f, off_the_grid, on_the_known_cell, cloud),
            std::numeric_limits<double>::infinity());
  EXPECT_EQ(GainInStandardErrors(grid, 0.9f, off_the_grid, on_the_known_cell, cloud), 0.0);
}

}  // namespace
}  // namespace mapping
}  // namespace fusemap
