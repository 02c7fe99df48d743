#ifndef FUSEMAP_MAPPING_SCAN_MATCHING_PRECOMPUTATION_GRID_2D_H_
#define FUSEMAP_MAPPING_SCAN_MATCHING_PRECOMPUTATION_GRID_2D_H_

#include <Eigen/Core>
#include <cassert>
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
// units. Strictly increasing in value_sum. Inline: branch and bound scores every candidate.
inline double PrecomputationScore(long value_sum, int num_points) {
  assert(num_points > 0);
  return kMinProbability + (kMaxProbability - kMinProbability) * static_cast<double>(value_sum) /
                               (static_cast<double>(kMaxPrecomputationValue) * num_points);
}

// Storage a rebuilt PrecomputationGridStack2D reuses. Local SLAM's wide search
// (InitialMatcher2D) rebuilds its stack after every insertion, megabytes for an open hall's
// submap: fresh allocations each time spent as long faulting in and zeroing pages as the
// stack's own arithmetic (orebro).
class PrecomputationBuffers {
 public:
  // A vector of `size` elements with unspecified values: the smallest buffer at hand that
  // holds `size` without growing, else the largest grown, else a new one.
  std::vector<uint8_t> Take(size_t size);
  void Give(std::vector<uint8_t> buffer);
  size_t count() const { return buffers_.size(); }
  // The precomputation value of each raw cell value (kUnknownValue as kMinProbability), made
  // on first use: 32768 conversions, which cost as much as a wide search's whole base level.
  const std::vector<uint8_t>& quantisation_table();

 private:
  std::vector<std::vector<uint8_t>> buffers_;
  std::vector<uint8_t> quantisation_table_;
};

// Cells min_cell + [0, num_x_cells) x [0, num_y_cells) of a grid; the box may reach past the
// grid.
struct CellBox {
  Eigen::Array2i min_cell = Eigen::Array2i::Zero();
  int num_x_cells = 0;
  int num_y_cells = 0;
};

// One level of the branch-and-bound pyramid (Hess et al. 2016, Sec. V-C, eq. 14). For width
// w = 2^depth, GetValue(c) must bound the quantised probabilities over the base-grid cells
// c + [0, w) x [0, w) (0 off the grid) from above; branch and bound stays exact with any such
// bound, and the tighter it is, the more it prunes.
//
// Depths 0 to 3 store that window maximum exactly, one byte per base cell each. Deeper
// levels store one value per block of b = w / 8 base cells per axis: the maximum over the
// nine blocks that a window of w starting in the block reaches (1.125 w). So the pyramid
// takes ~4.3 bytes per base cell, not one per cell and depth (8 at depth 7), and prunes
// nearly as well.
class PrecomputationGrid2D {
 public:
  // Depth 0 (w = 1): the grid's own cells, quantised.
  explicit PrecomputationGrid2D(const ProbabilityGrid& grid);

  int width_cells() const { return width_cells_; }
  // Memory held by the values.
  size_t bytes() const { return values_.capacity(); }
  // The bound for the window at `cell` (base-grid indices); 0 where the window is off the grid.
  int GetValue(const Eigen::Array2i& cell) const {
    // Arithmetic shift: floor division by the block size, negative cells included.
    const int x = (cell.x() >> block_shift_) - min_block_.x();
    const int y = (cell.y() >> block_shift_) - min_block_.y();
    if (x < 0 || y < 0 || x >= size_x_ || y >= size_y_) return 0;
    return values_[static_cast<size_t>(y) * size_x_ + x];
  }
  // The sum of GetValue(cell + offset) over `cells`, whose bounding box is [cells_min,
  // cells_max]; where the box (plus offset) lies on the grid, without a bounds check per cell
  // (branch and bound spends most of its time here).
  long SumValues(const std::vector<Eigen::Array2i>& cells, const Eigen::Array2i& cells_min,
                 const Eigen::Array2i& cells_max, const Eigen::Array2i& offset) const;
  // SumValues for each of the offsets first + (i * step, j * step), i in [0, num_x), j in
  // [0, num_y), into sums[i * num_y + j]: the same sums, a column of offsets (one i, up to 6
  // j; or 2 x 2 offsets) per pass over the points, their sums in registers, where offset by
  // offset every point is fetched and located again for each offset; where the lattice
  // reaches off the stored area, only the points it moves off are checked one by one. Branch
  // and bound scores 36 offsets per rotated scan at the lowest resolution of local SLAM's wide
  // search, and 4 children per expansion (the same poses to the byte; orebro 0.8x the CPU
  // time, intel's loop-closure searches 0.66x).
  void SumValuesOverOffsets(const std::vector<Eigen::Array2i>& cells,
                            const Eigen::Array2i& cells_min, const Eigen::Array2i& cells_max,
                            const Eigen::Array2i& first, int step, int num_x, int num_y,
                            long* sums) const;

 private:
  friend class PrecomputationGridStack2D;
  // Values for blocks min_block .. min_block + size - 1 (per axis) of 2^block_shift cells.
  PrecomputationGrid2D(int width_cells, int block_shift, const Eigen::Array2i& min_block,
                       int size_x, int size_y, std::vector<uint8_t> values);
  // Depth 0 over `box` of `grid`, in `values` (resized): its cells `stored` (in the box's
  // indices, inside the box) only, 0 elsewhere as off the grid.
  PrecomputationGrid2D(const ProbabilityGrid& grid, const CellBox& box, const CellBox& stored,
                       float unknown_probability, const std::vector<uint8_t>& quantisation_table,
                       std::vector<uint8_t> values);

  int width_cells_;
  int block_shift_;
  Eigen::Array2i min_block_;
  int size_x_;
  int size_y_;
  std::vector<uint8_t> values_;  // row-major, y outer
};

// Precomputation grids for depths 0 .. max_depth.
class PrecomputationGridStack2D {
 public:
  // With `buffers`, built in their storage (the values are the same either way) and its
  // scratch handed back to them.
  PrecomputationGridStack2D(const ProbabilityGrid& grid, int max_depth,
                            PrecomputationBuffers* buffers = nullptr);
  // Over `box` of `grid` only, its cell min_cell being the stack's cell 0. Cells the grid has
  // never observed, or that lie off it, score as `unknown_probability` where that is above
  // kMinProbability (else as the grid's own unknown cells). The same stack as one built over
  // the box copied into a grid of its own, without that copy: local SLAM's wide search
  // rebuilds its stack over the known part of the growing submap after every insertion.
  PrecomputationGridStack2D(const ProbabilityGrid& grid, const CellBox& box,
                            float unknown_probability, int max_depth,
                            PrecomputationBuffers* buffers = nullptr);
  // As above, for searches that read only the cells `reads` (the stack's indices) at any
  // depth: GetValue there is as above, and elsewhere unspecified. Built from the part of the
  // box those windows reach, not the whole box: local SLAM's wide search reads a few metres
  // around one scan, while an open hall's submap spans tens of metres (orebro: a scan's box
  // is a median 8 % of its submap's known area).
  PrecomputationGridStack2D(const ProbabilityGrid& grid, const CellBox& box,
                            float unknown_probability, int max_depth, const CellBox& reads,
                            PrecomputationBuffers* buffers = nullptr);

  // Hands every depth's storage to `buffers` for the next stack; this one is left empty
  // (max_depth() -1) and must not be matched against.
  void ReleaseInto(PrecomputationBuffers* buffers);

  const PrecomputationGrid2D& Get(int depth) const { return grids_.at(depth); }
  int max_depth() const { return static_cast<int>(grids_.size()) - 1; }
  // Memory held by all depths' values.
  size_t bytes() const;

 private:
  std::vector<PrecomputationGrid2D> grids_;
};

}  // namespace mapping
}  // namespace fusemap

#endif  // FUSEMAP_MAPPING_SCAN_MATCHING_PRECOMPUTATION_GRID_2D_H_
