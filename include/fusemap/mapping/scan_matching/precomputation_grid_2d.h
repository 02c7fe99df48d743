#ifndef FUSEMAP_MAPPING_SCAN_MATCHING_PRECOMPUTATION_GRID_2D_H_
#define FUSEMAP_MAPPING_SCAN_MATCHING_PRECOMPUTATION_GRID_2D_H_

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "fusemap/mapping/probability_grid.h"

namespace fusemap {
namespace mapping {

// Precomputed values quantise [kMinProbability, kMaxProbability] to [0, 255]; the branch and
// bound matcher scores candidates with these, so its scores are exact sums of small integers.
constexpr int kMaxPrecomputationValue = 255;
uint8_t ProbabilityToPrecomputationValue(float probability);
// Mean score of a candidate whose `num_points` values sum to `value_sum`, back in probability
// units. Strictly increasing in value_sum.
double PrecomputationScore(long value_sum, int num_points);

// One level of the branch-and-bound pyramid (Hess et al. 2016, Sec. V-C, eq. 14): for width
// w = 2^depth, the value at cell c is the maximum quantised probability over the base-grid cells
// c + [0, w) x [0, w), 0 where that window lies off the grid. It is stored for every c whose
// window touches the grid, i.e. c in [-(w - 1), num_cells - 1] per axis.
class PrecomputationGrid2D {
 public:
  // Depth 0 (w = 1): the grid's own cells, quantised.
  explicit PrecomputationGrid2D(const ProbabilityGrid& grid);
  // The next depth (twice the width), in O(cells) by taking the maximum of two half-width
  // windows along x, then along y.
  static PrecomputationGrid2D FromFinerLevel(const PrecomputationGrid2D& finer);

  int width_cells() const { return width_cells_; }
  // Max over the window at `cell` (base-grid indices); 0 outside the stored area.
  int GetValue(const Eigen::Array2i& cell) const {
    const int x = cell.x() - min_cell_.x();
    const int y = cell.y() - min_cell_.y();
    if (x < 0 || y < 0 || x >= size_x_ || y >= size_y_) return 0;
    return cells_[static_cast<size_t>(y) * size_x_ + x];
  }

 private:
  PrecomputationGrid2D(const Eigen::Array2i& min_cell, int size_x, int size_y, int width_cells);

  Eigen::Array2i min_cell_;  // base-grid index of the first stored cell
  int size_x_;
  int size_y_;
  int width_cells_;
  std::vector<uint8_t> cells_;  // row-major, y outer
};

// Precomputation grids for depths 0 .. max_depth.
class PrecomputationGridStack2D {
 public:
  PrecomputationGridStack2D(const ProbabilityGrid& grid, int max_depth);

  const PrecomputationGrid2D& Get(int depth) const { return grids_.at(depth); }
  int max_depth() const { return static_cast<int>(grids_.size()) - 1; }

 private:
  std::vector<PrecomputationGrid2D> grids_;
};

}  // namespace mapping
}  // namespace fusemap

#endif  // FUSEMAP_MAPPING_SCAN_MATCHING_PRECOMPUTATION_GRID_2D_H_
