#include "fusemap/mapping/grid_image.h"

#include <gtest/gtest.h>

namespace fusemap {
namespace mapping {
namespace {

ProbabilityGrid TenByTen() {
  MapLimits limits;
  limits.resolution_m = 0.1;
  limits.origin_m = Eigen::Vector2d(0.0, 0.0);
  limits.num_x_cells = 10;
  limits.num_y_cells = 10;
  return ProbabilityGrid(limits);
}

TEST(GridImageTest, PixelClasses) {
  EXPECT_EQ(ProbabilityToPixel(0.1f), kFreePixel);
  EXPECT_EQ(ProbabilityToPixel(0.34f), kFreePixel);
  EXPECT_EQ(ProbabilityToPixel(0.9f), kOccupiedPixel);
  EXPECT_EQ(ProbabilityToPixel(0.66f), kOccupiedPixel);
  EXPECT_EQ(ProbabilityToPixel(0.5f), 128);
  EXPECT_EQ(ProbabilityToPixel(0.6f), 102);
}

TEST(GridImageTest, EmptyGridGivesEmptyImage) {
  const ProbabilityGrid grid = TenByTen();
  const GridImage image = RenderGrid(grid);
  EXPECT_EQ(image.width, 0);
  EXPECT_TRUE(image.pixels.empty());
}

TEST(GridImageTest, SingleGridCoversKnownCellsWithYFlipped) {
  ProbabilityGrid grid = TenByTen();
  grid.SetProbability(Eigen::Array2i(2, 3), 0.9f);  // occupied, lower left of the known box
  grid.SetProbability(Eigen::Array2i(5, 7), 0.1f);  // free, upper right
  grid.SetProbability(Eigen::Array2i(4, 3), 0.5f);
  const GridImage image = RenderGrid(grid);
  ASSERT_EQ(image.width, 4);
  ASSERT_EQ(image.height, 5);
  EXPECT_NEAR(image.origin_m.x(), 0.2, 1e-9);
  EXPECT_NEAR(image.origin_m.y(), 0.3, 1e-9);
  EXPECT_EQ(image.at(4, 0), kOccupiedPixel);  // bottom row = min y
  EXPECT_EQ(image.at(0, 3), kFreePixel);      // top row = max y
  EXPECT_EQ(image.at(4, 2), 128);
  EXPECT_EQ(image.at(0, 0), kUnknownPixel);
  int unknown = 0;
  for (uint8_t p : image.pixels) unknown += p == kUnknownPixel;
  EXPECT_EQ(unknown, 20 - 3);
}

TEST(GridImageTest, PlacesGridsByTransformAndKeepsMostConfidentValue) {
  ProbabilityGrid a = TenByTen();
  ProbabilityGrid b = TenByTen();
  a.SetProbability(Eigen::Array2i(0, 0), 0.55f);
  a.SetProbability(Eigen::Array2i(1, 0), 0.2f);
  b.SetProbability(Eigen::Array2i(0, 0), 0.85f);
  b.SetProbability(Eigen::Array2i(1, 0), 0.45f);
  // Grid b is moved by one cell along +x in the map: its (0, 0) lands on a's (1, 0).
  const std::vector<PlacedGrid> grids = {
      {common::Rigid2d::Identity(), &a},
      {common::Rigid2d(0.1, 0.0, 0.0), &b}};
  const GridImage image = RenderMap(grids, 0.1);
  ASSERT_EQ(image.width, 3);
  ASSERT_EQ(image.height, 1);
  EXPECT_EQ(image.at(0, 0), ProbabilityToPixel(0.55f));
  EXPECT_EQ(image.at(0, 1), kOccupiedPixel);           // 0.85 beats 0.2 (|0.35| > |0.3|)
  EXPECT_EQ(image.at(0, 2), ProbabilityToPixel(0.45f));
}

TEST(GridImageTest, RotatedPlacement) {
  ProbabilityGrid grid = TenByTen();
  grid.SetProbability(Eigen::Array2i(5, 0), 0.9f);  // centre (0.55, 0.05)
  grid.SetProbability(Eigen::Array2i(0, 0), 0.1f);  // centre (0.05, 0.05)
  // A quarter turn maps (0.55, 0.05) to (-0.05, 0.55): the occupied cell ends up on top.
  const GridImage image = RenderMap({{common::Rigid2d(0.0, 0.0, M_PI / 2), &grid}}, 0.1);
  ASSERT_EQ(image.width, 1);
  ASSERT_EQ(image.height, 6);
  EXPECT_NEAR(image.origin_m.x(), -0.1, 1e-6);
  EXPECT_NEAR(image.origin_m.y(), 0.0, 1e-6);
  EXPECT_EQ(image.at(0, 0), kOccupiedPixel);
  EXPECT_EQ(image.at(5, 0), kFreePixel);
  EXPECT_EQ(image.at(2, 0), kUnknownPixel);
}

}  // namespace
}  // namespace mapping
}  // namespace fusemap
