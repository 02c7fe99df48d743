#include "fusemap/mapping/scan_matching/precomputation_grid_2d.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace fusemap {
namespace mapping {

uint8_t ProbabilityToPrecomputationValue(float probability) {
  const float p = std::clamp(probability, kMinProbability, kMaxProbability);
  return static_cast<uint8_t>(
      std::lround((p - kMinProbability) * (kMaxPrecomputationValue / (kMaxProbability - kMinProbability))));
}

double PrecomputationScore(long value_sum, int num_points) {
  assert(num_points > 0);
  return kMinProbability + (kMaxProbability - kMinProbability) * static_cast<double>(value_sum) /
                               (static_cast<double>(kMaxPrecomputationValue) * num_points);
}

PrecomputationGrid2D::PrecomputationGrid2D(const Eigen::Array2i& min_cell, int size_x, int size_y,
                                           int width_cells)
    : min_cell_(min_cell),
      size_x_(size_x),
      size_y_(size_y),
      width_cells_(width_cells),
      cells_(static_cast<size_t>(size_x) * size_y, 0) {}

PrecomputationGrid2D::PrecomputationGrid2D(const ProbabilityGrid& grid)
    : PrecomputationGrid2D(Eigen::Array2i::Zero(), grid.limits().num_x_cells,
                           grid.limits().num_y_cells, 1) {
  for (int y = 0; y < size_y_; ++y) {
    for (int x = 0; x < size_x_; ++x) {
      cells_[static_cast<size_t>(y) * size_x_ + x] =
          ProbabilityToPrecomputationValue(grid.GetProbability(Eigen::Array2i(x, y)));
    }
  }
}

PrecomputationGrid2D PrecomputationGrid2D::FromFinerLevel(const PrecomputationGrid2D& finer) {
  const int half = finer.width_cells_;
  const int width = 2 * half;
  // The base grid spans [0, n) with n = finer size - (half - 1); stored c in [-(w-1), n-1].
  const Eigen::Array2i min_cell = Eigen::Array2i::Constant(-(width - 1));
  const int size_x = finer.size_x_ + half;
  const int size_y = finer.size_y_ + half;

  // Along x: window [c, c + w) = [c, c + half) u [c + half, c + w); rows keep the finer range.
  PrecomputationGrid2D along_x(Eigen::Array2i(min_cell.x(), finer.min_cell_.y()), size_x,
                               finer.size_y_, width);
  for (int j = 0; j < finer.size_y_; ++j) {
    const int y = finer.min_cell_.y() + j;
    for (int i = 0; i < size_x; ++i) {
      const int x = min_cell.x() + i;
      along_x.cells_[static_cast<size_t>(j) * size_x + i] = static_cast<uint8_t>(
          std::max(finer.GetValue(Eigen::Array2i(x, y)), finer.GetValue(Eigen::Array2i(x + half, y))));
    }
  }
  PrecomputationGrid2D coarser(min_cell, size_x, size_y, width);
  for (int j = 0; j < size_y; ++j) {
    const int y = min_cell.y() + j;
    for (int i = 0; i < size_x; ++i) {
      const int x = min_cell.x() + i;
      coarser.cells_[static_cast<size_t>(j) * size_x + i] = static_cast<uint8_t>(std::max(
          along_x.GetValue(Eigen::Array2i(x, y)), along_x.GetValue(Eigen::Array2i(x, y + half))));
    }
  }
  return coarser;
}

PrecomputationGridStack2D::PrecomputationGridStack2D(const ProbabilityGrid& grid, int max_depth) {
  assert(max_depth >= 0);
  grids_.reserve(max_depth + 1);
  grids_.emplace_back(grid);
  for (int depth = 1; depth <= max_depth; ++depth) {
    grids_.push_back(PrecomputationGrid2D::FromFinerLevel(grids_.back()));
  }
}

}  // namespace mapping
}  // namespace fusemap
