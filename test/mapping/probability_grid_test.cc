#include "fusemap/mapping/probability_grid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace fusemap {
namespace mapping {
namespace {

MapLimits SmallLimits() {
  MapLimits limits;
  limits.resolution_m = 0.1;
  limits.origin_m = Eigen::Vector2d(-1.0, -1.0);
  limits.num_x_cells = 20;
  limits.num_y_cells = 20;
  return limits;
}

TEST(ProbabilityGridTest, StartsUnknown) {
  ProbabilityGrid grid(SmallLimits());
  EXPECT_FALSE(grid.IsKnown(Eigen::Array2i(3, 4)));
  EXPECT_FLOAT_EQ(grid.GetProbability(Eigen::Array2i(3, 4)), kMinProbability);
  EXPECT_FLOAT_EQ(grid.GetProbability(Eigen::Array2i(-1, 400)), kMinProbability);
  Eigen::Array2i lo, hi;
  EXPECT_FALSE(grid.ComputeKnownBounds(&lo, &hi));
}

TEST(ProbabilityGridTest, GetProbabilityOrReadsUnknownCellsAsGiven) {
  ProbabilityGrid grid(SmallLimits());
  grid.SetProbability(Eigen::Array2i(2, 2), 0.8f);
  EXPECT_FLOAT_EQ(grid.GetProbabilityOr(Eigen::Array2i(2, 2), 0.5f), grid.GetProbability(Eigen::Array2i(2, 2)));
  EXPECT_FLOAT_EQ(grid.GetProbabilityOr(Eigen::Array2i(3, 4), 0.5f), 0.5f);
  EXPECT_FLOAT_EQ(grid.GetProbabilityOr(Eigen::Array2i(-1, 400), 0.5f), 0.5f);
  EXPECT_FLOAT_EQ(grid.GetProbabilityOr(Eigen::Array2i(3, 4), kMinProbability), kMinProbability);
}

TEST(ProbabilityGridTest, MarkedCellIsNotUpdatedTwiceInOneScan) {
  ProbabilityGrid grid(SmallLimits());
  const auto hit = ComputeLookupTableToApplyOdds(Odds(0.55f));
  const Eigen::Array2i cell(5, 5);
  EXPECT_TRUE(grid.ApplyLookupTable(cell, hit));
  EXPECT_FALSE(grid.ApplyLookupTable(cell, hit));
  EXPECT_NEAR(grid.GetProbability(cell), 0.55f, 1e-4f);
  grid.FinishUpdate();
  EXPECT_TRUE(grid.ApplyLookupTable(cell, hit));
  grid.FinishUpdate();
  EXPECT_NEAR(grid.GetProbability(cell), ProbabilityFromOdds(Odds(0.55f) * Odds(0.55f)), 1e-4f);
}

TEST(ProbabilityGridTest, GrowKeepsContentsAtTheSameWorldPositions) {
  ProbabilityGrid grid(SmallLimits());
  const std::vector<std::pair<Eigen::Vector2f, float>> marks = {
      {{-0.95f, -0.95f}, 0.2f}, {{0.55f, 0.25f}, 0.8f}, {{0.95f, 0.95f}, 0.7f}};
  for (const auto& [point, p] : marks) {
    grid.SetProbability(grid.limits().GetCellIndex(point), p);
  }
  grid.GrowLimits(Eigen::Vector2f(7.3f, -4.2f));
  const MapLimits& grown = grid.limits();
  EXPECT_GT(grown.num_x_cells, 20);
  const Eigen::Array2i far_cell = grown.GetCellIndex(Eigen::Vector2f(7.3f, -4.2f));
  EXPECT_TRUE(grown.Contains(far_cell));
  EXPECT_NEAR(grown.resolution_m, 0.1, 1e-12);
  for (const auto& [point, p] : marks) {
    EXPECT_NEAR(grid.GetProbability(grown.GetCellIndex(point)), p, 1e-4f);
  }
  Eigen::Array2i lo, hi;
  ASSERT_TRUE(grid.ComputeKnownBounds(&lo, &hi));
  EXPECT_NEAR(grown.GetCellCenter(lo).x(), -0.95, 1e-6);
  EXPECT_NEAR(grown.GetCellCenter(hi).y(), 0.95, 1e-6);
  // Exactly three known cells survive.
  int known = 0;
  for (int y = 0; y < grown.num_y_cells; ++y) {
    for (int x = 0; x < grown.num_x_cells; ++x) known += grid.IsKnown(Eigen::Array2i(x, y));
  }
  EXPECT_EQ(known, 3);
}

// The known bounds are kept up to date by writes rather than scanned for: after lookup-table
// updates, direct writes, growth and cropping they equal a scan of every cell.
TEST(ProbabilityGridTest, KnownBoundsFollowEveryWrite) {
  const auto scanned = [](const ProbabilityGrid& grid, Eigen::Array2i* lo, Eigen::Array2i* hi) {
    bool any = false;
    for (int y = 0; y < grid.limits().num_y_cells; ++y) {
      for (int x = 0; x < grid.limits().num_x_cells; ++x) {
        const Eigen::Array2i c(x, y);
        if (!grid.IsKnown(c)) continue;
        *lo = any ? lo->min(c) : c;
        *hi = any ? hi->max(c) : c;
        any = true;
      }
    }
    return any;
  };
  const auto expect_bounds_as_scanned = [&scanned](const ProbabilityGrid& grid, int step) {
    Eigen::Array2i lo, hi, scan_lo, scan_hi;
    const bool any = grid.ComputeKnownBounds(&lo, &hi);
    ASSERT_EQ(any, scanned(grid, &scan_lo, &scan_hi)) << "step " << step;
    if (!any) return;
    EXPECT_EQ(lo.x(), scan_lo.x()) << "step " << step;
    EXPECT_EQ(lo.y(), scan_lo.y()) << "step " << step;
    EXPECT_EQ(hi.x(), scan_hi.x()) << "step " << step;
    EXPECT_EQ(hi.y(), scan_hi.y()) << "step " << step;
  };
  ProbabilityGrid grid(SmallLimits());
  const std::vector<uint16_t> table = ComputeLookupTableToApplyOdds(Odds(0.55f));
  expect_bounds_as_scanned(grid, 0);
  grid.ApplyLookupTable(Eigen::Array2i(7, 3), table);
  grid.FinishUpdate();
  expect_bounds_as_scanned(grid, 1);
  grid.SetProbability(Eigen::Array2i(2, 15), 0.3f);
  expect_bounds_as_scanned(grid, 2);
  grid.GrowLimits(Eigen::Vector2f(-6.f, 9.f));
  expect_bounds_as_scanned(grid, 3);
  const Eigen::Array2i far = grid.limits().GetCellIndex(Eigen::Vector2f(-5.5f, 8.5f));
  grid.ApplyLookupTable(far, table);
  grid.FinishUpdate();
  expect_bounds_as_scanned(grid, 4);
  const ProbabilityGrid cropped = grid.Cropped();
  expect_bounds_as_scanned(cropped, 5);
  const ProbabilityGrid restored(cropped.limits(), cropped.cells());
  expect_bounds_as_scanned(restored, 6);
}

// A grid built from cell values (checkpoint restore, the wide search's pooled grid) finds its
// known box from each row's first and last known cell.
TEST(ProbabilityGridTest, GridFromCellsKnowsTheBoxOfItsKnownCells) {
  MapLimits limits = SmallLimits();
  std::vector<uint16_t> cells(static_cast<size_t>(limits.num_x_cells) * limits.num_y_cells,
                              kUnknownValue);
  const auto set = [&](int x, int y) {
    cells[limits.FlatIndex(Eigen::Array2i(x, y))] = ProbabilityToValue(0.7f);
  };
  {
    const ProbabilityGrid empty(limits, cells);
    Eigen::Array2i lo, hi;
    EXPECT_FALSE(empty.ComputeKnownBounds(&lo, &hi));
  }
  set(5, 4);   // a row with one known cell
  set(3, 9);   // a row with known cells at both ends, unknown between
  set(11, 9);
  set(8, 12);
  const ProbabilityGrid grid(limits, cells);
  Eigen::Array2i lo, hi;
  ASSERT_TRUE(grid.ComputeKnownBounds(&lo, &hi));
  EXPECT_EQ(lo.x(), 3);
  EXPECT_EQ(lo.y(), 4);
  EXPECT_EQ(hi.x(), 11);
  EXPECT_EQ(hi.y(), 12);
  set(0, 0);
  set(limits.num_x_cells - 1, limits.num_y_cells - 1);
  const ProbabilityGrid corners(limits, cells);
  ASSERT_TRUE(corners.ComputeKnownBounds(&lo, &hi));
  EXPECT_TRUE((lo == Eigen::Array2i(0, 0)).all());
  EXPECT_TRUE((hi == Eigen::Array2i(limits.num_x_cells - 1, limits.num_y_cells - 1)).all());
}

TEST(ProbabilityGridTest, GrowIsANoOpForInteriorPoints) {
  ProbabilityGrid grid(SmallLimits());
  grid.GrowLimits(Eigen::Vector2f(0.f, 0.f));
  EXPECT_EQ(grid.limits().num_x_cells, 20);
  EXPECT_NEAR(grid.limits().origin_m.x(), -1.0, 1e-12);
}

TEST(ProbabilityGridTest, CroppedKeepsKnownCellsAtTheirWorldPositions) {
  MapLimits limits;
  limits.resolution_m = 0.1;
  limits.origin_m = Eigen::Vector2d(-5.0, -5.0);
  limits.num_x_cells = 100;
  limits.num_y_cells = 100;
  ProbabilityGrid grid(limits);
  grid.SetProbability(Eigen::Array2i(10, 20), 0.8f);
  grid.SetProbability(Eigen::Array2i(30, 25), 0.2f);
  const ProbabilityGrid cropped = grid.Cropped();
  EXPECT_EQ(cropped.limits().num_x_cells, 21);
  EXPECT_EQ(cropped.limits().num_y_cells, 6);
  for (const Eigen::Array2i& cell : {Eigen::Array2i(10, 20), Eigen::Array2i(30, 25)}) {
    const Eigen::Vector2f world = limits.GetCellCenter(cell).cast<float>();
    EXPECT_NEAR(cropped.GetProbability(cropped.limits().GetCellIndex(world)),
                grid.GetProbability(cell), 1e-6);
  }
}

// Issue 18, item 3: a point at 1e300 overflowed the doubling loop's int arithmetic and hung.
TEST(ProbabilityGridTest, RefusesToGrowForAbsurdOrNonFinitePoints) {
  ProbabilityGrid grid(SmallLimits());
  const MapLimits before = grid.limits();
  const float inf = std::numeric_limits<float>::infinity();
  for (const Eigen::Vector2f& p :
       {Eigen::Vector2f(1e30f, 0.f), Eigen::Vector2f(0.f, -3e38f), Eigen::Vector2f(inf, 0.f),
        Eigen::Vector2f(0.f, std::nanf("")), Eigen::Vector2f(1e5f, 1e5f)}) {
    EXPECT_FALSE(grid.GrowLimits(p)) << p.transpose();
    EXPECT_EQ(grid.limits().num_x_cells, before.num_x_cells);
    EXPECT_EQ(grid.limits().origin_m, before.origin_m);
  }
  // All or nothing for a box with one good and one absurd corner.
  EXPECT_FALSE(grid.GrowLimits(Eigen::Vector2f(5.f, 5.f), Eigen::Vector2f(1e30f, 5.f)));
  EXPECT_EQ(grid.limits().num_x_cells, before.num_x_cells);
  // The bound in cells, asked without allocating. Only the axes that fall short grow, towards
  // the side that does: with 10 m cells from x, y = -100 m, 200 km on both axes needs
  // 20 x 2^10 = 20,480 cells per side (4.2e8 cells), past it; 50 km needs 5,120 per side.
  MapLimits coarse = SmallLimits();
  coarse.resolution_m = 10.0;
  coarse.origin_m = Eigen::Vector2d(-100.0, -100.0);
  EXPECT_FALSE(ProbabilityGrid::LimitsCovering(coarse, Eigen::Vector2f(2e5f, 2e5f),
                                               Eigen::Vector2f(2e5f, 2e5f)));
  const auto limits = ProbabilityGrid::LimitsCovering(coarse, Eigen::Vector2f(0.f, -5e4f), Eigen::Vector2f(5e4f, 0.f));
  ASSERT_TRUE(limits.has_value());
  EXPECT_EQ(limits->num_x_cells, 5120);
  EXPECT_EQ(limits->num_y_cells, 5120);
  EXPECT_EQ(limits->origin_m.x(), -100.0);  // grown towards +x only
  EXPECT_LT(limits->origin_m.y(), -5e4);    // grown towards -y only
  EXPECT_EQ(limits->origin_m.y() + 10.0 * limits->num_y_cells, -100.0 + 10.0 * 20);
  // A long strip grows along its length only.
  const auto strip = ProbabilityGrid::LimitsCovering(coarse, Eigen::Vector2f(1e5f, 0.f),
                                                     Eigen::Vector2f(1e5f, 0.f));
  ASSERT_TRUE(strip.has_value());
  EXPECT_EQ(strip->num_y_cells, 20);
  // Ordinary growth still works: 0.1 m cells from x = -1 m reach 30 m at 320 cells.
  EXPECT_TRUE(grid.GrowLimits(Eigen::Vector2f(30.f, -30.f)));
  EXPECT_EQ(grid.limits().num_x_cells, 320);
  EXPECT_EQ(grid.limits().num_y_cells, 320);
}

}  // namespace
}  // namespace mapping
}  // namespace fusemap
