#include "fusemap/mapping/scan_matching/precomputation_grid_2d.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace fusemap {
namespace mapping {
namespace {

ProbabilityGrid MakeRandomGrid(int num_x, int num_y, unsigned seed) {
  MapLimits limits;
  limits.num_x_cells = num_x;
  limits.num_y_cells = num_y;
  ProbabilityGrid grid(limits);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> probability(0.f, 1.f);
  for (int y = 0; y < num_y; ++y) {
    for (int x = 0; x < num_x; ++x) {
      const float p = probability(rng);
      if (p < 0.2f) continue;  // leave some cells unknown
      grid.SetProbability(Eigen::Array2i(x, y), p);
    }
  }
  return grid;
}

// A discretised scan of `num_cells` random cells (x in [0, max_coordinate], y in half that),
// with its bounding box.
struct RandomScan {
  std::vector<Eigen::Array2i> cells;
  Eigen::Array2i min_cell;
  Eigen::Array2i max_cell;
};

RandomScan MakeRandomScan(int num_cells, int max_coordinate, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> coordinate(0, max_coordinate);
  RandomScan scan;
  for (int i = 0; i < num_cells; ++i) {
    const int x = coordinate(rng);
    scan.cells.emplace_back(x, coordinate(rng) / 2);
  }
  scan.min_cell = scan.max_cell = scan.cells.front();
  for (const Eigen::Array2i& cell : scan.cells) {
    scan.min_cell = scan.min_cell.min(cell);
    scan.max_cell = scan.max_cell.max(cell);
  }
  return scan;
}

int NaiveWindowMax(const ProbabilityGrid& grid, const Eigen::Array2i& cell, int width) {
  int value = 0;
  for (int dy = 0; dy < width; ++dy) {
    for (int dx = 0; dx < width; ++dx) {
      value = std::max<int>(value, ProbabilityToPrecomputationValue(
                                       grid.GetProbability(cell + Eigen::Array2i(dx, dy))));
    }
  }
  return value;
}

TEST(PrecomputationGrid2DTest, QuantisationEndsAndScore) {
  EXPECT_EQ(ProbabilityToPrecomputationValue(kMinProbability), 0);
  EXPECT_EQ(ProbabilityToPrecomputationValue(0.f), 0);
  EXPECT_EQ(ProbabilityToPrecomputationValue(kMaxProbability), 255);
  EXPECT_EQ(ProbabilityToPrecomputationValue(0.3f), 64);  // 63.75 rounds up
  EXPECT_NEAR(PrecomputationScore(0, 10), kMinProbability, 1e-6);
  EXPECT_NEAR(PrecomputationScore(2550, 10), kMaxProbability, 1e-6);
  EXPECT_LT(PrecomputationScore(1000, 10), PrecomputationScore(1001, 10));
}

TEST(PrecomputationGrid2DTest, EveryDepthBoundsItsWindowAsDocumented) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const ProbabilityGrid grid = MakeRandomGrid(37 + seed, 23, seed);
    const PrecomputationGridStack2D stack(grid, 5);
    ASSERT_EQ(stack.max_depth(), 5);
    for (int depth = 0; depth <= stack.max_depth(); ++depth) {
      const PrecomputationGrid2D& level = stack.Get(depth);
      const int width = 1 << depth;
      ASSERT_EQ(level.width_cells(), width);
      // Reach beyond the stored area on every side, where the value must be 0.
      for (int y = -2 * width - 2; y < grid.limits().num_y_cells + 2; ++y) {
        for (int x = -2 * width - 2; x < grid.limits().num_x_cells + 2; ++x) {
          const Eigen::Array2i cell(x, y);
          const int value = level.GetValue(cell);
          const int window_max = NaiveWindowMax(grid, cell, width);
          if (depth <= 3) {
            ASSERT_EQ(value, window_max) << "seed " << seed << " depth " << depth << " cell " << x
                                         << "," << y;
            continue;
          }
          // Deeper: the maximum over the nine blocks of w / 8 from the cell's block on.
          const int block = width / 8;
          const auto block_start = [block](int c) {
            return c >= 0 ? c / block * block : -((-c + block - 1) / block) * block;
          };
          const Eigen::Array2i start(block_start(x), block_start(y));
          int coverage_max = 0;
          for (int dy = 0; dy < 9 * block; ++dy) {
            for (int dx = 0; dx < 9 * block; ++dx) {
              coverage_max = std::max<int>(
                  coverage_max, ProbabilityToPrecomputationValue(
                                    grid.GetProbability(start + Eigen::Array2i(dx, dy))));
            }
          }
          ASSERT_GE(value, window_max) << "seed " << seed << " depth " << depth << " cell " << x
                                       << "," << y;
          ASSERT_EQ(value, coverage_max) << "seed " << seed << " depth " << depth << " cell " << x
                                         << "," << y;
        }
      }
    }
  }
}

// SumValues is the sum of GetValue at every depth, exact and blocked, wherever the scan's box
// lands: inside the stored area (its unchecked path), across its edge, or off it.
TEST(PrecomputationGrid2DTest, SumValuesIsTheSumOfGetValue) {
  const ProbabilityGrid grid = MakeRandomGrid(60, 45, 7);
  const PrecomputationGridStack2D stack(grid, 6);
  const RandomScan scan = MakeRandomScan(40, 30, 11);
  int checked_inside = 0;
  for (int depth = 0; depth <= stack.max_depth(); ++depth) {
    const PrecomputationGrid2D& level = stack.Get(depth);
    for (int oy = -80; oy <= 60; oy += 7) {
      for (int ox = -90; ox <= 70; ox += 9) {
        const Eigen::Array2i offset(ox, oy);
        long expected = 0;
        for (const Eigen::Array2i& cell : scan.cells) expected += level.GetValue(cell + offset);
        ASSERT_EQ(level.SumValues(scan.cells, scan.min_cell, scan.max_cell, offset), expected)
            << "depth " << depth << " offset " << ox << " " << oy;
        if (ox >= 0 && oy >= 0 && ox + scan.max_cell.x() < 60 && oy + scan.max_cell.y() < 45) {
          ++checked_inside;
        }
      }
    }
  }
  EXPECT_GT(checked_inside, 10);
}

// SumValuesOverOffsets gives SumValues at each offset of its lattice: steps of whole blocks
// (a pass per column of up to 6 rows, or the 2 x 2 children in one) and of part blocks (per
// offset), 1 to 8 rows, on the stored area (unchecked), across its edge (the points that
// leave it checked) and off it.
TEST(PrecomputationGrid2DTest, SumValuesOverOffsetsIsSumValuesAtEachOffset) {
  const ProbabilityGrid grid = MakeRandomGrid(70, 50, 5);
  const PrecomputationGridStack2D stack(grid, 6);
  const RandomScan scan = MakeRandomScan(30, 24, 13);
  int checked_inside = 0;
  for (int depth = 0; depth <= stack.max_depth(); ++depth) {
    const PrecomputationGrid2D& level = stack.Get(depth);
    for (int step : {1, 2, 3, 4, 8, 16}) {
      for (int num_x : {1, 2, 6}) {
        for (int num_y : {1, 2, 3, 5, 6, 8}) {
          for (const Eigen::Array2i& first :
               {Eigen::Array2i(3, 2), Eigen::Array2i(-5, 1), Eigen::Array2i(40, 30)}) {
            std::vector<long> sums(static_cast<size_t>(num_x) * num_y, -1);
            level.SumValuesOverOffsets(scan.cells, scan.min_cell, scan.max_cell, first, step, num_x,
                                       num_y, sums.data());
            for (int i = 0; i < num_x; ++i) {
              for (int j = 0; j < num_y; ++j) {
                const Eigen::Array2i offset = first + step * Eigen::Array2i(i, j);
                ASSERT_EQ(sums[i * num_y + j],
                          level.SumValues(scan.cells, scan.min_cell, scan.max_cell, offset))
                    << "depth " << depth << " step " << step << " offset " << offset.x() << " "
                    << offset.y();
              }
            }
            const Eigen::Array2i last = first + step * Eigen::Array2i(num_x - 1, num_y - 1);
            if ((first + scan.min_cell).minCoeff() >= 0 && (last + scan.max_cell).x() < 70 &&
                (last + scan.max_cell).y() < 50) {
              ++checked_inside;
            }
          }
        }
      }
    }
  }
  EXPECT_GT(checked_inside, 100);
}

TEST(PrecomputationGrid2DTest, SingleOccupiedCellSpreadsBackwards) {
  MapLimits limits;
  limits.num_x_cells = 8;
  limits.num_y_cells = 8;
  ProbabilityGrid grid(limits);
  grid.SetProbability(Eigen::Array2i(5, 2), kMaxProbability);
  const PrecomputationGridStack2D stack(grid, 4);
  // Width 4 (exact): windows starting at x in [2, 5] and y in [-1, 2] contain (5, 2).
  EXPECT_EQ(stack.Get(2).GetValue(Eigen::Array2i(2, -1)), 255);
  EXPECT_EQ(stack.Get(2).GetValue(Eigen::Array2i(5, 2)), 255);
  EXPECT_EQ(stack.Get(2).GetValue(Eigen::Array2i(1, 2)), 0);
  EXPECT_EQ(stack.Get(2).GetValue(Eigen::Array2i(5, 3)), 0);
  // Width 16, blocks of 2: (5, 2) is in block (2, 1), reached from blocks x in [-6, 2] and
  // y in [-7, 1], i.e. from cells x in [-12, 5] and y in [-14, 3].
  EXPECT_EQ(stack.Get(4).GetValue(Eigen::Array2i(-12, -14)), 255);
  EXPECT_EQ(stack.Get(4).GetValue(Eigen::Array2i(5, 3)), 255);
  EXPECT_EQ(stack.Get(4).GetValue(Eigen::Array2i(-13, 2)), 0);
  EXPECT_EQ(stack.Get(4).GetValue(Eigen::Array2i(5, 4)), 0);
  EXPECT_EQ(stack.Get(4).GetValue(Eigen::Array2i(6, 2)), 0);
}

TEST(PrecomputationGrid2DTest, DeepPyramidTakesUnderFiveBytesPerCell) {
  const ProbabilityGrid grid = MakeRandomGrid(400, 300, 4);
  const PrecomputationGridStack2D stack(grid, 7);
  const double cells = 400.0 * 300.0;
  // One byte per cell at depths 0 to 3, a quarter of the previous depth's below (8 when every
  // depth was stored per cell).
  EXPECT_LT(stack.bytes() / cells, 5.0);
  EXPECT_GT(stack.bytes() / cells, 4.0);
}

// A stack built in recycled storage (InitialMatcher2D rebuilds one after every insertion)
// holds exactly the values of a fresh one, whatever the storage held before (the levels of a
// larger or a smaller grid), and the storage does not grow from one rebuild to the next.
TEST(PrecomputationGridStack2DTest, RecycledStorageGivesTheSameValues) {
  const ProbabilityGrid large = MakeRandomGrid(61, 47, 7);
  const ProbabilityGrid small = MakeRandomGrid(29, 33, 8);
  PrecomputationBuffers buffers;
  size_t buffers_after_first_round = 0;
  for (int round = 0; round < 3; ++round) {
    for (const ProbabilityGrid* grid : {&large, &small}) {
      PrecomputationGridStack2D recycled(*grid, 5, &buffers);
      const PrecomputationGridStack2D fresh(*grid, 5);
      ASSERT_EQ(recycled.max_depth(), fresh.max_depth());
      for (int depth = 0; depth <= fresh.max_depth(); ++depth) {
        const int width = 1 << depth;
        for (int y = -2 * width - 2; y < grid->limits().num_y_cells + 2; ++y) {
          for (int x = -2 * width - 2; x < grid->limits().num_x_cells + 2; ++x) {
            const Eigen::Array2i cell(x, y);
            ASSERT_EQ(recycled.Get(depth).GetValue(cell), fresh.Get(depth).GetValue(cell))
                << "round " << round << " depth " << depth << " cell " << x << "," << y;
          }
        }
      }
      recycled.ReleaseInto(&buffers);
      EXPECT_EQ(recycled.max_depth(), -1);
    }
    if (round == 0) buffers_after_first_round = buffers.count();
    EXPECT_EQ(buffers.count(), buffers_after_first_round) << "round " << round;
  }
  EXPECT_GT(buffers_after_first_round, 0u);
}

// A stack over a box of a grid (InitialMatcher2D's, over the known part of the submap plus
// padding) holds exactly the values of a stack over that box copied into a grid of its own,
// the box's unknown and off-grid cells set to the unknown probability, at every depth; with
// the unknown probability at kMinProbability, the grid's own unknown cells stay as they are.
TEST(PrecomputationGridStack2DTest, StackOverABoxEqualsStackOverItsCopy) {
  const ProbabilityGrid grid = MakeRandomGrid(41, 29, 11);
  struct Case {
    CellBox box;
    float unknown_probability;
  };
  const std::vector<Case> cases = {
      {CellBox{Eigen::Array2i(-6, -4), 53, 40}, 0.5f},            // past every side
      {CellBox{Eigen::Array2i(5, 3), 20, 11}, 0.5f},              // inside
      {CellBox{Eigen::Array2i(30, -2), 25, 9}, kMinProbability},  // past two sides
      {CellBox{Eigen::Array2i(50, 40), 4, 3}, 0.6f},              // off the grid
  };
  for (const Case& c : cases) {
    MapLimits limits;
    limits.num_x_cells = c.box.num_x_cells;
    limits.num_y_cells = c.box.num_y_cells;
    ProbabilityGrid copy(limits);
    for (int y = 0; y < limits.num_y_cells; ++y) {
      for (int x = 0; x < limits.num_x_cells; ++x) {
        const Eigen::Array2i cell = c.box.min_cell + Eigen::Array2i(x, y);
        const bool known = grid.limits().Contains(cell) && grid.IsKnown(cell);
        if (known) {
          copy.SetProbability(Eigen::Array2i(x, y), grid.GetProbability(cell));
        } else if (c.unknown_probability > kMinProbability) {
          copy.SetProbability(Eigen::Array2i(x, y), c.unknown_probability);
        }
      }
    }
    const PrecomputationGridStack2D from_box(grid, c.box, c.unknown_probability, 3);
    const PrecomputationGridStack2D from_copy(copy, 3);
    ASSERT_EQ(from_box.max_depth(), 3);
    for (int depth = 0; depth <= 3; ++depth) {
      for (int y = -10; y < limits.num_y_cells + 2; ++y) {
        for (int x = -10; x < limits.num_x_cells + 2; ++x) {
          const Eigen::Array2i cell(x, y);
          ASSERT_EQ(from_box.Get(depth).GetValue(cell), from_copy.Get(depth).GetValue(cell))
              << "box at " << c.box.min_cell.transpose() << " depth " << depth << " cell " << x
              << "," << y;
        }
      }
    }
  }
}

// A stack built for the cells a search reads holds, at every depth (exact and blocked), the
// values of the stack over the whole box at those cells: reads inside the box, across its
// edges, off it, and in storage recycled from one case to the next.
TEST(PrecomputationGridStack2DTest, StackForTheCellsReadEqualsTheWholeStackThere) {
  const ProbabilityGrid grid = MakeRandomGrid(250, 200, 12);
  const CellBox box{Eigen::Array2i(-5, -3), 257, 210};
  const std::vector<CellBox> all_reads = {
      CellBox{Eigen::Array2i(20, 15), 17, 9},     // inside
      CellBox{Eigen::Array2i(-12, -7), 30, 25},   // past the low sides
      CellBox{Eigen::Array2i(230, 190), 40, 33},  // past the high sides
      CellBox{Eigen::Array2i(33, 41), 1, 1},      // one cell, off the blocks' boundaries
      CellBox{Eigen::Array2i(300, 5), 6, 6},      // off the box
      CellBox{Eigen::Array2i(-90, -90), 8, 8},    // off the box, below
  };
  PrecomputationBuffers buffers;
  for (int max_depth : {2, 5, 6}) {
    const PrecomputationGridStack2D whole(grid, box, 0.5f, max_depth);
    for (const CellBox& reads : all_reads) {
      PrecomputationGridStack2D part(grid, box, 0.5f, max_depth, reads, &buffers);
      ASSERT_EQ(part.max_depth(), max_depth);
      for (int depth = 0; depth <= max_depth; ++depth) {
        for (int y = reads.min_cell.y(); y < reads.min_cell.y() + reads.num_y_cells; ++y) {
          for (int x = reads.min_cell.x(); x < reads.min_cell.x() + reads.num_x_cells; ++x) {
            const Eigen::Array2i cell(x, y);
            ASSERT_EQ(part.Get(depth).GetValue(cell), whole.Get(depth).GetValue(cell))
                << "reads at " << reads.min_cell.transpose() << " depth " << depth << " of "
                << max_depth << " cell " << x << "," << y;
          }
        }
      }
      part.ReleaseInto(&buffers);
    }
  }
  // Built from part of the box only: a few cells' stack takes a fraction of the whole's.
  const CellBox few{Eigen::Array2i(20, 15), 10, 10};
  EXPECT_LT(PrecomputationGridStack2D(grid, box, 0.5f, 2, few).bytes(),
            PrecomputationGridStack2D(grid, box, 0.5f, 2).bytes() / 4);
}

// Take hands out the smallest buffer that holds the size, else the largest, grown.
TEST(PrecomputationBuffersTest, TakesTheSmallestThatFitsElseTheLargest) {
  PrecomputationBuffers buffers;
  for (size_t size : {100u, 400u, 200u}) buffers.Give(std::vector<uint8_t>(size));
  buffers.Give(std::vector<uint8_t>());  // nothing to reuse: not kept
  ASSERT_EQ(buffers.count(), 3u);
  std::vector<uint8_t> fits = buffers.Take(150);
  EXPECT_EQ(fits.size(), 150u);
  EXPECT_EQ(fits.capacity(), 200u);
  std::vector<uint8_t> grown = buffers.Take(1000);
  EXPECT_EQ(grown.size(), 1000u);
  EXPECT_EQ(buffers.count(), 1u);
  EXPECT_EQ(buffers.Take(50).capacity(), 100u);
  EXPECT_EQ(buffers.count(), 0u);
  EXPECT_EQ(buffers.Take(10).size(), 10u);  // none left: a new one
}

}  // namespace
}  // namespace mapping
}  // namespace fusemap
