#include "fusemap/pose_graph/overlapping_submaps_trimmer_2d.h"

#include <gtest/gtest.h>

#include <functional>
#include <memory>

namespace fusemap {
namespace pose_graph {
namespace {

constexpr double kResolutionM = 0.05;

using GridSource = std::function<std::shared_ptr<const mapping::ProbabilityGrid>()>;

// Sets the cells of [x0_m, x1_m) x [0, height_m) to `probability`.
void FillRectangle(double x0_m, double x1_m, double height_m, float probability,
                   mapping::ProbabilityGrid* grid) {
  for (int y = 0; y < static_cast<int>(height_m / kResolutionM + 0.5); ++y) {
    for (int x = static_cast<int>(x0_m / kResolutionM + 0.5);
         x < static_cast<int>(x1_m / kResolutionM + 0.5); ++x) {
      grid->SetProbability(Eigen::Array2i(x, y), probability);
    }
  }
}

std::shared_ptr<mapping::ProbabilityGrid> EmptyGrid() {
  mapping::MapLimits limits;
  limits.resolution_m = kResolutionM;
  limits.num_x_cells = 100;
  limits.num_y_cells = 100;
  return std::make_shared<mapping::ProbabilityGrid>(limits);
}

GridSource Source(std::shared_ptr<mapping::ProbabilityGrid> grid) {
  return [grid]() -> std::shared_ptr<const mapping::ProbabilityGrid> { return grid; };
}

// A 5 m x 5 m grid whose known cells are the rectangle [0, width_m) x [0, height_m), seen free
// many times (probability 0.2), as the trimmer fetches it.
GridSource KnownRectangle(double width_m, double height_m) {
  auto grid = EmptyGrid();
  FillRectangle(0.0, width_m, height_m, 0.2f, grid.get());
  return Source(grid);
}

OverlappingSubmapsTrimmerOptions2D Options(int fresh) {
  OverlappingSubmapsTrimmerOptions2D options;
  options.fresh_submaps_count = fresh;
  options.min_covered_area_m2 = 1.0;
  return options;
}

TEST(OverlappingSubmapsTrimmerTest, KeepsOnlyTheFreshestOfIdenticalSubmaps) {
  const auto grid = KnownRectangle(3.0, 3.0);
  const std::vector<PlacedSubmap2D> submaps = {{0, common::Rigid2d::Identity(), grid},
                                               {3, common::Rigid2d::Identity(), grid},
                                               {7, common::Rigid2d::Identity(), grid}};
  EXPECT_EQ(FindSubmapsToTrim(submaps, Options(1)), (std::vector<int>{0, 3}));
  EXPECT_EQ(FindSubmapsToTrim(submaps, Options(2)), (std::vector<int>{0}));
  EXPECT_TRUE(FindSubmapsToTrim(submaps, Options(3)).empty());
}

TEST(OverlappingSubmapsTrimmerTest, OldSubmapSurvivesWhereItAloneCoversEnoughArea) {
  // The old submaps are 3 m x 3 m; the new one covers their left 2.5 m or 2.9 m, so the first
  // old one alone covers 0.5 m x 3 m = 1.5 m^2 and the second 0.1 m x 3 m = 0.3 m^2.
  const auto old_grid = KnownRectangle(3.0, 3.0);
  const auto new_wide = KnownRectangle(2.5, 3.0);
  const auto new_wider = KnownRectangle(2.9, 3.0);
  EXPECT_TRUE(FindSubmapsToTrim({{0, common::Rigid2d::Identity(), old_grid},
                                 {1, common::Rigid2d::Identity(), new_wide}},
                                Options(1))
                  .empty());
  EXPECT_EQ(FindSubmapsToTrim({{0, common::Rigid2d::Identity(), old_grid},
                               {1, common::Rigid2d::Identity(), new_wider}},
                              Options(1)),
            (std::vector<int>{0}));
}

// The bug: every pass through a building glances through doorways at angles no later pass
// repeats; cells crossed by a ray or two kept each pass's old submaps alive, and the submaps
// held grew lap after lap (intel played 12 times: 25 after the first lap, 82 after the 12th).
TEST(OverlappingSubmapsTrimmerTest, CellsOnlyGlancedAtDoNotKeepASubmap) {
  // Both submaps know [0, 3 m) x [0, 3 m) well; the old one also glanced at 1 m x 3 m = 3 m^2
  // beyond it (one miss: 0.49, one hit: 0.55), the new one did not.
  auto old_grid = EmptyGrid();
  FillRectangle(0.0, 3.0, 3.0, 0.2f, old_grid.get());
  FillRectangle(3.0, 3.5, 3.0, 0.49f, old_grid.get());
  FillRectangle(3.5, 4.0, 3.0, 0.55f, old_grid.get());
  const std::vector<PlacedSubmap2D> submaps = {
      {0, common::Rigid2d::Identity(), Source(old_grid)},
      {1, common::Rigid2d::Identity(), KnownRectangle(3.0, 3.0)}};
  OverlappingSubmapsTrimmerOptions2D options = Options(1);
  EXPECT_EQ(FindSubmapsToTrim(submaps, options), (std::vector<int>{0}));
  // Where the old submap knows the same strip well (seen occupied again and again), it holds
  // area no newer submap has and stays.
  FillRectangle(3.0, 4.0, 3.0, 0.8f, old_grid.get());
  EXPECT_TRUE(FindSubmapsToTrim(submaps, options).empty());
  // A margin of 0 counts every known cell, as before.
  FillRectangle(3.0, 4.0, 3.0, 0.49f, old_grid.get());
  options.min_probability_margin = 0.0;
  EXPECT_TRUE(FindSubmapsToTrim(submaps, options).empty());
}

TEST(OverlappingSubmapsTrimmerTest, CoverageIsComparedInTheMapFrame) {
  const auto grid = KnownRectangle(3.0, 3.0);
  // The same grid placed 10 m away covers other map cells; a quarter turn about the
  // rectangle's centre covers the same ones.
  const common::Rigid2d far(Eigen::Vector2d(10.0, 0.0), 0.0);
  const common::Rigid2d turned =
      common::Rigid2d(Eigen::Vector2d(1.5, 1.5), M_PI / 2) *
      common::Rigid2d(Eigen::Vector2d(-1.5, -1.5), 0.0);
  EXPECT_TRUE(FindSubmapsToTrim({{0, common::Rigid2d::Identity(), grid},
                                 {1, far, grid}},
                                Options(1))
                  .empty());
  EXPECT_EQ(FindSubmapsToTrim({{0, common::Rigid2d::Identity(), grid},
                               {1, turned, grid}},
                              Options(1)),
            (std::vector<int>{0}));
}

TEST(OverlappingSubmapsTrimmerTest, UnknownGridIsTrimmed) {
  const auto empty = KnownRectangle(0.0, 0.0);
  const auto grid = KnownRectangle(3.0, 3.0);
  EXPECT_EQ(FindSubmapsToTrim({{0, common::Rigid2d::Identity(), grid},
                               {1, common::Rigid2d::Identity(), empty}},
                              Options(1)),
            (std::vector<int>{1}));
}

TEST(OverlappingSubmapsTrimmerTest, OptionsValidation) {
  std::string error;
  OverlappingSubmapsTrimmerOptions2D options;
  EXPECT_TRUE(options.IsValid(&error));
  EXPECT_FALSE(options.enabled());
  options.fresh_submaps_count = OverlappingSubmapsTrimmerOptions2D::kMaxFreshSubmaps + 1;
  EXPECT_FALSE(options.IsValid(&error));
  options.fresh_submaps_count = 1;
  options.min_added_submaps_count = 0;
  EXPECT_FALSE(options.IsValid(&error));
  options.min_added_submaps_count = 1;
  options.min_covered_area_m2 = -1.0;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("min_covered_area_m2"), std::string::npos);
  options.min_covered_area_m2 = 2.0;
  options.min_probability_margin = 0.5;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("min_probability_margin"), std::string::npos);
  options.min_probability_margin = -0.1;
  EXPECT_FALSE(options.IsValid(&error));
}

}  // namespace
}  // namespace pose_graph
}  // namespace fusemap
