#include "fusemap/mapping/range_data_inserter_2d.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fusemap {
namespace mapping {
namespace {

constexpr float kValueTol = 1e-4f;
constexpr double kResolution = 0.05;

ProbabilityGrid SmallGrid() {
  MapLimits limits;
  limits.resolution_m = kResolution;
  limits.origin_m = Eigen::Vector2d(-0.5, -0.5);
  limits.num_x_cells = 20;
  limits.num_y_cells = 20;
  return ProbabilityGrid(limits);
}

// A scan of a square room with walls at |x| = |y| = kHalfSide, taken from `origin`, with the
// beams in [gap_begin, gap_end) rad seeing nothing up to 1.5 m (an open door): misses.
constexpr float kHalfSide = 2.f;
sensor::RangeData SquareRoomScan(const Eigen::Vector2f& origin, float gap_begin, float gap_end) {
  sensor::RangeData data;
  data.origin = origin;
  constexpr int kNumBeams = 720;
  for (int i = 0; i < kNumBeams; ++i) {
    const float a = 2.f * static_cast<float>(M_PI) * i / kNumBeams - static_cast<float>(M_PI);
    const Eigen::Vector2f d(std::cos(a), std::sin(a));
    if (a >= gap_begin && a < gap_end) {
      data.misses.push_back(origin + 1.5f * d);
      continue;
    }
    float range = 1e9f;
    if (d.x() > 1e-6f) range = std::min(range, (kHalfSide - origin.x()) / d.x());
    if (d.x() < -1e-6f) range = std::min(range, (-kHalfSide - origin.x()) / d.x());
    if (d.y() > 1e-6f) range = std::min(range, (kHalfSide - origin.y()) / d.y());
    if (d.y() < -1e-6f) range = std::min(range, (-kHalfSide - origin.y()) / d.y());
    // Pull the return 1 mm inside so it falls in the cell on the room side of the wall.
    data.returns.push_back(origin + (range - 1e-3f) * d);
  }
  return data;
}

float ProbabilityAt(const ProbabilityGrid& grid, float x, float y) {
  return grid.GetProbability(grid.limits().GetCellIndex(Eigen::Vector2f(x, y)));
}
bool KnownAt(const ProbabilityGrid& grid, float x, float y) {
  return grid.IsKnown(grid.limits().GetCellIndex(Eigen::Vector2f(x, y)));
}

TEST(RangeDataInserter2DTest, SquareRoomFromTheCentre) {
  ProbabilityGrid grid = SmallGrid();
  const RangeDataInserter2D inserter{ProbabilityGridRangeDataInserterOptions()};
  // Door: beams pointing at angles in [-0.2, 0.2) rad (towards +x) see no return.
  const sensor::RangeData scan = SquareRoomScan(Eigen::Vector2f(0.1f, 0.2f), -0.2f, 0.2f);
  inserter.Insert(scan, &grid);

  // The grid grew to cover the whole room.
  EXPECT_TRUE(grid.limits().Contains(grid.limits().GetCellIndex(Eigen::Vector2f(-2.f, -2.f))));
  // Wall cells are hits (0.55 after one scan), except the door.
  for (float t = -1.9f; t <= 1.9f; t += 0.1f) {
    EXPECT_NEAR(ProbabilityAt(grid, t, 1.99f), 0.55f, kValueTol) << t;
    EXPECT_NEAR(ProbabilityAt(grid, -1.99f, t), 0.55f, kValueTol) << t;
    EXPECT_NEAR(ProbabilityAt(grid, t, -1.99f), 0.55f, kValueTol) << t;
  }
  // Free space between robot and walls is a miss (0.49).
  for (float t = -1.8f; t <= 1.8f; t += 0.3f) {
    // Along +x the door's misses end at x = 1.6.
    if (t < 1.5f) {
      EXPECT_NEAR(ProbabilityAt(grid, t, 0.2f), 0.49f, kValueTol) << t;
    }
    EXPECT_NEAR(ProbabilityAt(grid, 0.1f, t), 0.49f, kValueTol) << t;
    EXPECT_NEAR(ProbabilityAt(grid, 0.6f * t, -0.9f * t), 0.49f, kValueTol) << t;
  }
  // Behind walls nothing is known.
  for (float t = -1.8f; t <= 1.8f; t += 0.3f) {
    EXPECT_FALSE(KnownAt(grid, t, 2.3f)) << t;
    EXPECT_FALSE(KnownAt(grid, -2.3f, t)) << t;
  }
  // Door: free up to 1.5 m from the robot along +x (end cell included), unknown beyond.
  EXPECT_NEAR(ProbabilityAt(grid, 1.55f, 0.2f), 0.49f, kValueTol);
  EXPECT_FALSE(KnownAt(grid, 1.7f, 0.2f));
  EXPECT_FALSE(KnownAt(grid, 1.99f, 0.2f));
}

TEST(RangeDataInserter2DTest, RepeatedScansConvergeTowardsClamps) {
  ProbabilityGrid grid = SmallGrid();
  const RangeDataInserter2D inserter{ProbabilityGridRangeDataInserterOptions()};
  const sensor::RangeData scan = SquareRoomScan(Eigen::Vector2f(0.f, 0.f), 10.f, 10.f);
  inserter.Insert(scan, &grid);
  inserter.Insert(scan, &grid);
  // Exactly one update per cell per scan: two hits give odds(0.55)^2.
  EXPECT_NEAR(ProbabilityAt(grid, 0.5f, 1.99f),
              ProbabilityFromOdds(Odds(0.55f) * Odds(0.55f)), kValueTol);
  EXPECT_NEAR(ProbabilityAt(grid, 0.5f, 1.f),
              ProbabilityFromOdds(Odds(0.49f) * Odds(0.49f)), kValueTol);
  // About 10 hits reach 0.9 and 55 misses reach 0.1 (odds ratios 1.22 and 0.96 per scan).
  for (int i = 0; i < 80; ++i) inserter.Insert(scan, &grid);
  EXPECT_NEAR(ProbabilityAt(grid, 0.5f, 1.99f), kMaxProbability, kValueTol);
  EXPECT_NEAR(ProbabilityAt(grid, 0.5f, 1.f), kMinProbability, kValueTol);
}

TEST(RangeDataInserter2DTest, HitCellIsNotClearedByAnotherRayOfTheSameScan) {
  ProbabilityGrid grid = SmallGrid();
  const RangeDataInserter2D inserter{ProbabilityGridRangeDataInserterOptions()};
  sensor::RangeData data;
  data.origin = Eigen::Vector2f(0.01f, 0.01f);
  data.returns = {{0.31f, 0.01f}, {0.61f, 0.01f}};  // the ray to the second crosses the first
  data.misses = {{0.41f, 0.01f}};
  inserter.Insert(data, &grid);
  EXPECT_NEAR(ProbabilityAt(grid, 0.31f, 0.01f), 0.55f, kValueTol);
  EXPECT_NEAR(ProbabilityAt(grid, 0.61f, 0.01f), 0.55f, kValueTol);
  EXPECT_NEAR(ProbabilityAt(grid, 0.46f, 0.01f), 0.49f, kValueTol);
  EXPECT_NEAR(ProbabilityAt(grid, 0.01f, 0.01f), 0.49f, kValueTol);
}

TEST(RangeDataInserter2DTest, DiagonalRayVisitsAConnectedChainOfCells) {
  ProbabilityGrid grid = SmallGrid();
  const RangeDataInserter2D inserter{ProbabilityGridRangeDataInserterOptions()};
  sensor::RangeData data;
  data.origin = Eigen::Vector2f(0.013f, 0.021f);
  const Eigen::Vector2f end(-1.377f, 0.912f);
  data.misses = {end};
  inserter.Insert(data, &grid);
  // Every cell the segment passes through is free, and a 4-connected walk from the first to
  // the last cell visits exactly |dx| + |dy| + 1 cells, so nothing else was touched.
  const MapLimits& limits = grid.limits();
  int on_ray = 0;
  for (int i = 0; i <= 1000; ++i) {
    const Eigen::Vector2f p = data.origin + (end - data.origin) * (i / 1000.f);
    EXPECT_NEAR(grid.GetProbability(limits.GetCellIndex(p)), 0.49f, kValueTol) << i;
  }
  for (int y = 0; y < limits.num_y_cells; ++y) {
    for (int x = 0; x < limits.num_x_cells; ++x) on_ray += grid.IsKnown(Eigen::Array2i(x, y));
  }
  const Eigen::Array2i d = limits.GetCellIndex(end) - limits.GetCellIndex(data.origin);
  EXPECT_EQ(on_ray, std::abs(d.x()) + std::abs(d.y()) + 1);
}

TEST(RangeDataInserter2DTest, WithoutFreeSpaceOnlyHitsAreInserted) {
  ProbabilityGrid grid = SmallGrid();
  ProbabilityGridRangeDataInserterOptions options;
  options.insert_free_space = false;
  const RangeDataInserter2D inserter(options);
  inserter.Insert(SquareRoomScan(Eigen::Vector2f(0.f, 0.f), -0.2f, 0.2f), &grid);
  EXPECT_NEAR(ProbabilityAt(grid, 0.5f, 1.99f), 0.55f, kValueTol);
  EXPECT_FALSE(KnownAt(grid, 0.5f, 1.f));
  EXPECT_FALSE(KnownAt(grid, 1.f, 0.f));
}

TEST(ProbabilityGridRangeDataInserterOptionsTest, ParseAndValidate) {
  std::string error;
  auto reader = common::ConfigReader::FromString(
      "hit_probability: 0.6\nmiss_probability: 0.4\ninsert_free_space: false\n", "i.yaml",
      &error);
  ASSERT_NE(reader, nullptr) << error;
  const auto options = ParseProbabilityGridRangeDataInserterOptions(*reader);
  EXPECT_TRUE(reader->Finish(&error)) << error;
  EXPECT_FLOAT_EQ(options.hit_probability, 0.6f);
  EXPECT_FLOAT_EQ(options.miss_probability, 0.4f);
  EXPECT_FALSE(options.insert_free_space);
  auto bad = common::ConfigReader::FromString("hit_probability: 0.4\n", "b.yaml", &error);
  ParseProbabilityGridRangeDataInserterOptions(*bad);
  EXPECT_FALSE(bad->Finish(&error));
}

// Issue 18, item 3: range data far away (a pose at 1e300, a non-finite point) is refused as a
// whole and leaves the grid as it was, instead of growing it without end.
TEST(RangeDataInserter2DTest, RefusesAbsurdRangeDataAndLeavesTheGridUnchanged) {
  ProbabilityGridRangeDataInserterOptions options;
  RangeDataInserter2D inserter(options);
  ProbabilityGrid grid = SmallGrid();
  sensor::RangeData far;
  far.origin = Eigen::Vector2f(0.f, 0.f);
  far.returns.push_back(Eigen::Vector2f(1.f, 0.f));
  far.returns.push_back(Eigen::Vector2f(3e37f, 1.f));
  EXPECT_FALSE(inserter.Insert(far, &grid));
  sensor::RangeData nan = far;
  nan.returns[1] = Eigen::Vector2f(std::nanf(""), 0.f);
  EXPECT_FALSE(inserter.Insert(nan, &grid));
  EXPECT_EQ(grid.limits().num_x_cells, SmallGrid().limits().num_x_cells);
  Eigen::Array2i lo, hi;
  EXPECT_FALSE(grid.ComputeKnownBounds(&lo, &hi));
  far.returns.pop_back();
  EXPECT_TRUE(inserter.Insert(far, &grid));
  EXPECT_TRUE(grid.ComputeKnownBounds(&lo, &hi));
}

}  // namespace
}  // namespace mapping
}  // namespace fusemap
