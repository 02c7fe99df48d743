#include "occupied_space_cost_function_2d.h"

#include <gtest/gtest.h>

#include <memory>

namespace fusemap {
namespace mapping {
namespace {

ProbabilityGrid MakeGrid() {
  MapLimits limits;
  limits.resolution_m = 0.1;
  limits.origin_m = Eigen::Vector2d(-1.0, -1.0);
  limits.num_x_cells = 20;
  limits.num_y_cells = 20;
  ProbabilityGrid grid(limits);
  grid.SetProbability(Eigen::Array2i(12, 7), 0.9f);
  grid.SetProbability(Eigen::Array2i(13, 7), 0.5f);
  return grid;
}

TEST(OccupiedSpaceCostFunction2DTest, InterpolatesThroughCellCentres) {
  const ProbabilityGrid grid = MakeGrid();
  // Cell (12, 7) has its centre at (0.25, -0.25); the pose moves the point there.
  const sensor::PointCloud2d cloud = {Eigen::Vector2f(0.f, 0.f), Eigen::Vector2f(0.1f, 0.f)};
  std::unique_ptr<ceres::CostFunction> cost(
      CreateOccupiedSpaceCostFunction2D(2.0, cloud, grid, kMinProbability));
  ASSERT_EQ(cost->num_residuals(), 2);
  const double pose[3] = {0.25, -0.25, 0.0};
  const double* parameters[] = {pose};
  double residuals[2];
  double jacobian[6];
  double* jacobians[] = {jacobian};
  ASSERT_TRUE(cost->Evaluate(parameters, residuals, jacobians));
  EXPECT_NEAR(residuals[0], 2.0 * (1.0 - grid.GetProbability(Eigen::Array2i(12, 7))), 1e-6);
  EXPECT_NEAR(residuals[1], 2.0 * (1.0 - grid.GetProbability(Eigen::Array2i(13, 7))), 1e-6);
  // The cubic Hermite (Catmull-Rom) slope at a sample is the central difference of its
  // neighbours: cells (11, 7) = 0.1 and (13, 7) = 0.5, one cell = 0.1 m apart.
  EXPECT_NEAR(jacobian[0], 2.0 * ((1.0 - 0.5) - (1.0 - 0.1)) / (2.0 * 0.1), 1e-4);
  EXPECT_NEAR(jacobian[1], 0.0, 1e-9);
}

TEST(OccupiedSpaceCostFunction2DTest, OutsideTheGridAndNeverObservedCostAsUnknown) {
  const ProbabilityGrid grid = MakeGrid();
  // Far outside the grid, and inside it in a cell nothing observed (cell (3, 3)).
  const sensor::PointCloud2d cloud = {Eigen::Vector2f(50.f, -30.f), Eigen::Vector2f(-0.65f, -0.65f)};
  for (const float unknown : {kMinProbability, 0.5f}) {
    std::unique_ptr<ceres::CostFunction> cost(
        CreateOccupiedSpaceCostFunction2D(1.0, cloud, grid, unknown));
    const double pose[3] = {0.0, 0.0, 0.0};
    const double* parameters[] = {pose};
    double residuals[2];
    double jacobian[6];
    double* jacobians[] = {jacobian};
    ASSERT_TRUE(cost->Evaluate(parameters, residuals, jacobians));
    EXPECT_NEAR(residuals[0], 1.0 - unknown, 1e-6);
    EXPECT_NEAR(residuals[1], 1.0 - unknown, 1e-6);
    EXPECT_NEAR(jacobian[0], 0.0, 1e-12);
    EXPECT_NEAR(jacobian[2], 0.0, 1e-12);
  }
}

}  // namespace
}  // namespace mapping
}  // namespace fusemap
