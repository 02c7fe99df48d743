#include "fusemap/pose_graph/overlapping_submaps_trimmer_2d.h"

#include <gtest/gtest.h>

#include <functional>
#include <memory>

namespace fusemap {
namespace pose_graph {
namespace {

constexpr double kResolutionM = 0.05;

using GridSource = std::function<std::shared_ptr<const mapping::ProbabilityGrid>()>;

// A 5 m x 5 m grid whose known cells are the rectangle [0, width_m) x [0, height_m), as the
// trimmer fetches it.
GridSource KnownRectangle(double width_m, double height_m) {
  mapping::MapLimits limits;
  limits.resolution_m = kResolutionM;
  limits.num_x_cells = 100;
  limits.num_y_cells = 100;
  auto grid = std::make_shared<mapping::ProbabilityGrid>(limits);
  for (int y = 0; y < static_cast<int>(height_m / kResolutionM + 0.5); ++y) {
    for (int x = 0; x < static_cast<int>(width_m / kResolutionM + 0.5); ++x) {
      grid->SetProbability(Eigen::Array2i(x, y), 0.2f);
    }
  }
  return [grid]() -> std::shared_ptr<const mapping::ProbabilityGrid> { return grid; };
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
}

}  // namespace
}  // namespace pose_graph
}  // namespace fusemap
