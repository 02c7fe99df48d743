#include "fusemap/mapping/scan_matching/precomputation_grid_2d.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <type_traits>
#include <utility>

namespace fusemap {
namespace mapping {

uint8_t ProbabilityToPrecomputationValue(float probability) {
  const float p = std::clamp(probability, kMinProbability, kMaxProbability);
  return static_cast<uint8_t>(
      std::lround((p - kMinProbability) * (kMaxPrecomputationValue / (kMaxProbability - kMinProbability))));
}

namespace {

// Depths up to this one are stored exactly (one byte per cell each); deeper ones in blocks of
// 2^(depth - kExactDepths) cells. On Intel, 3 kept loop-closure search within ~12 % of
// all-exact levels; at 1 or 2 the looser bounds made it 1.6-1.9x slower.
constexpr int kExactDepths = 3;

std::vector<uint8_t> TakeBuffer(PrecomputationBuffers* buffers, size_t size) {
  return buffers != nullptr ? buffers->Take(size) : std::vector<uint8_t>(size);
}

void GiveBuffer(PrecomputationBuffers* buffers, std::vector<uint8_t> buffer) {
  if (buffers != nullptr) buffers->Give(std::move(buffer));
}

// See PrecomputationBuffers::quantisation_table.
std::vector<uint8_t> MakeQuantisationTable() {
  std::vector<uint8_t> table(kMaxValue + 1);
  for (int value = 0; value <= kMaxValue; ++value) {
    table[value] =
        ProbabilityToPrecomputationValue(ValueToProbability(static_cast<uint16_t>(value)));
  }
  return table;
}

CellBox WholeGrid(const ProbabilityGrid& grid) {
  return CellBox{Eigen::Array2i::Zero(), grid.limits().num_x_cells, grid.limits().num_y_cells};
}

// Values for indices [min, min + size) per axis, row-major; 0 elsewhere.
struct Plane {
  Eigen::Array2i min = Eigen::Array2i::Zero();
  int size_x = 0;
  int size_y = 0;
  std::vector<uint8_t> values;
};

// A plane read in place: a scratch Plane or a stored level, which is not copied.
struct PlaneView {
  Eigen::Array2i min;
  int size_x;
  int size_y;
  const uint8_t* values;
  uint8_t At(int x, int y) const {
    x -= min.x();
    y -= min.y();
    if (x < 0 || y < 0 || x >= size_x || y >= size_y) return 0;
    return values[static_cast<size_t>(y) * size_x + x];
  }
};

PlaneView View(const Plane& plane) {
  return {plane.min, plane.size_x, plane.size_y, plane.values.data()};
}

// Maximum over 2 x 2 blocks: block maxima at twice the block size (`in` starts at an even
// index, so that its blocks pair up as the whole grid's do). Every output value is written, so
// `buffers` may hand out storage with stale values.
Plane HalveByMax(const PlaneView& in, PrecomputationBuffers* buffers) {
  assert(in.min.x() % 2 == 0 && in.min.y() % 2 == 0);
  Plane out;
  out.min = in.min / 2;
  out.size_x = (in.size_x + 1) / 2;
  out.size_y = (in.size_y + 1) / 2;
  out.values = TakeBuffer(buffers, static_cast<size_t>(out.size_x) * out.size_y);
  for (int j = 0; j < out.size_y; ++j) {
    const int y = out.min.y() + j;
    for (int i = 0; i < out.size_x; ++i) {
      const int x = out.min.x() + i;
      out.values[static_cast<size_t>(j) * out.size_x + i] =
          std::max(std::max(in.At(2 * x, 2 * y), in.At(2 * x + 1, 2 * y)),
                   std::max(in.At(2 * x, 2 * y + 1), in.At(2 * x + 1, 2 * y + 1)));
    }
  }
  return out;
}

// out(k) = max over j in [0, n) of in(k + j * stride), per axis, for every k whose terms touch
// `in`: k from in.min - (n - 1) * stride on. Separable: along x, then along y, on whole rows
// (these planes have millions of cells and are rebuilt during local SLAM). Every output value
// is written, as in HalveByMax.
Plane MaxOfStrided(const PlaneView& in, int n, int stride, PrecomputationBuffers* buffers) {
  const int reach = (n - 1) * stride;
  Plane along_x;
  along_x.min = Eigen::Array2i(in.min.x() - reach, in.min.y());
  along_x.size_x = in.size_x + reach;
  along_x.size_y = in.size_y;
  along_x.values = TakeBuffer(buffers, static_cast<size_t>(along_x.size_x) * along_x.size_y);
  // One input row with `reach` zeros on both sides: output i reads padded[i + t * stride].
  std::vector<uint8_t> padded = TakeBuffer(buffers, static_cast<size_t>(in.size_x) + 2 * reach);
  std::fill(padded.begin(), padded.end(), 0);
  for (int y = 0; y < in.size_y; ++y) {
    std::copy_n(in.values + static_cast<size_t>(y) * in.size_x, in.size_x, padded.begin() + reach);
    uint8_t* out_row = along_x.values.data() + static_cast<size_t>(y) * along_x.size_x;
    std::copy_n(padded.begin(), along_x.size_x, out_row);
    for (int t = 1; t < n; ++t) {
      const uint8_t* source = padded.data() + t * stride;
      for (int i = 0; i < along_x.size_x; ++i) out_row[i] = std::max(out_row[i], source[i]);
    }
  }
  Plane out;
  out.min = Eigen::Array2i(along_x.min.x(), in.min.y() - reach);
  out.size_x = along_x.size_x;
  out.size_y = in.size_y + reach;
  out.values = TakeBuffer(buffers, static_cast<size_t>(out.size_x) * out.size_y);
  for (int j = 0; j < out.size_y; ++j) {
    uint8_t* out_row = out.values.data() + static_cast<size_t>(j) * out.size_x;
    bool written = false;
    for (int t = 0; t < n; ++t) {
      const int source_row = j - reach + t * stride;
      if (source_row < 0 || source_row >= along_x.size_y) continue;
      const uint8_t* source = along_x.values.data() + static_cast<size_t>(source_row) * out.size_x;
      if (!written) {
        std::copy_n(source, out.size_x, out_row);
        written = true;
        continue;
      }
      for (int i = 0; i < out.size_x; ++i) out_row[i] = std::max(out_row[i], source[i]);
    }
    if (!written) std::fill_n(out_row, out.size_x, 0);
  }
  GiveBuffer(buffers, std::move(along_x.values));
  GiveBuffer(buffers, std::move(padded));
  return out;
}

}  // namespace

std::vector<uint8_t> PrecomputationBuffers::Take(size_t size) {
  auto best = buffers_.end();
  for (auto it = buffers_.begin(); it != buffers_.end(); ++it) {
    if (best == buffers_.end()) {
      best = it;
      continue;
    }
    const bool fits = it->capacity() >= size;
    const bool best_fits = best->capacity() >= size;
    if (fits ? (!best_fits || it->capacity() < best->capacity())
             : (!best_fits && it->capacity() > best->capacity())) {
      best = it;
    }
  }
  std::vector<uint8_t> buffer;
  if (best != buffers_.end()) {
    buffer = std::move(*best);
    buffers_.erase(best);
  }
  buffer.resize(size);
  return buffer;
}

void PrecomputationBuffers::Give(std::vector<uint8_t> buffer) {
  if (buffer.capacity() == 0) return;  // nothing to reuse
  buffers_.push_back(std::move(buffer));
}

const std::vector<uint8_t>& PrecomputationBuffers::quantisation_table() {
  if (quantisation_table_.empty()) quantisation_table_ = MakeQuantisationTable();
  return quantisation_table_;
}

PrecomputationGrid2D::PrecomputationGrid2D(int width_cells, int block_shift,
                                           const Eigen::Array2i& min_block, int size_x, int size_y,
                                           std::vector<uint8_t> values)
    : width_cells_(width_cells),
      block_shift_(block_shift),
      min_block_(min_block),
      size_x_(size_x),
      size_y_(size_y),
      values_(std::move(values)) {
  assert(values_.size() == static_cast<size_t>(size_x_) * size_y_);
}

PrecomputationGrid2D::PrecomputationGrid2D(const ProbabilityGrid& grid)
    : PrecomputationGrid2D(grid, WholeGrid(grid), WholeGrid(grid), kMinProbability,
                           MakeQuantisationTable(), std::vector<uint8_t>()) {}

PrecomputationGrid2D::PrecomputationGrid2D(const ProbabilityGrid& grid, const CellBox& box,
                                           const CellBox& stored, float unknown_probability,
                                           const std::vector<uint8_t>& quantisation_table,
                                           std::vector<uint8_t> values)
    : width_cells_(1),
      block_shift_(0),
      min_block_(stored.min_cell),
      size_x_(stored.num_x_cells),
      size_y_(stored.num_y_cells),
      values_(std::move(values)) {
  assert(stored.min_cell.minCoeff() >= 0 &&
         stored.min_cell.x() + stored.num_x_cells <= box.num_x_cells &&
         stored.min_cell.y() + stored.num_y_cells <= box.num_y_cells);
  // The grid's index of stored cell 0.
  const Eigen::Array2i stored_min = box.min_cell + stored.min_cell;
  values_.resize(static_cast<size_t>(size_x_) * size_y_);
  const std::vector<uint16_t>& cells = grid.cells();
  // Raw cells quantised through a table: millions of cells, 32768 possible values.
  assert(quantisation_table.size() == kMaxValue + 1u);
  std::vector<uint8_t> table = quantisation_table;
  if (unknown_probability > kMinProbability) {
    table[kUnknownValue] = table[ProbabilityToValue(unknown_probability)];
  }
  const uint8_t unknown = table[kUnknownValue];
  const int grid_size_x = grid.limits().num_x_cells;
  const int grid_size_y = grid.limits().num_y_cells;
  // The stored columns that lie on the grid: [first_x, end_x) from the first stored one.
  const int first_x = std::clamp(-stored_min.x(), 0, size_x_);
  const int end_x = std::clamp(grid_size_x - stored_min.x(), first_x, size_x_);
  for (int y = 0; y < size_y_; ++y) {
    uint8_t* const row = values_.data() + static_cast<size_t>(y) * size_x_;
    const int grid_y = stored_min.y() + y;
    if (grid_y < 0 || grid_y >= grid_size_y) {
      std::fill_n(row, size_x_, unknown);
      continue;
    }
    std::fill_n(row, first_x, unknown);
    const uint16_t* const grid_row = cells.data() + static_cast<size_t>(grid_y) * grid_size_x;
    for (int x = first_x; x < end_x; ++x) {
      row[x] = table[grid_row[stored_min.x() + x] & static_cast<uint16_t>(~kUpdateMarker)];
    }
    std::fill(row + end_x, row + size_x_, unknown);
  }
}

long PrecomputationGrid2D::SumValues(const std::vector<Eigen::Array2i>& cells,
                                     const Eigen::Array2i& cells_min,
                                     const Eigen::Array2i& cells_max,
                                     const Eigen::Array2i& offset) const {
  // Blocks are monotonic in the cell index, so the box's corner blocks bound every cell's.
  const Eigen::Array2i low = cells_min + offset;
  const Eigen::Array2i high = cells_max + offset;
  const bool on_grid = (low.x() >> block_shift_) >= min_block_.x() &&
                       (low.y() >> block_shift_) >= min_block_.y() &&
                       (high.x() >> block_shift_) < min_block_.x() + size_x_ &&
                       (high.y() >> block_shift_) < min_block_.y() + size_y_;
  long sum = 0;
  if (!on_grid) {
    for (const Eigen::Array2i& cell : cells) sum += GetValue(cell + offset);
    return sum;
  }
  const uint8_t* const values = values_.data();
  if (block_shift_ == 0) {
    const long base = static_cast<long>(offset.y() - min_block_.y()) * size_x_ +
                      (offset.x() - min_block_.x());
    for (const Eigen::Array2i& cell : cells) {
      sum += values[base + static_cast<long>(cell.y()) * size_x_ + cell.x()];
    }
    return sum;
  }
  for (const Eigen::Array2i& cell : cells) {
    const Eigen::Array2i shifted = cell + offset;
    sum += values[static_cast<size_t>((shifted.y() >> block_shift_) - min_block_.y()) * size_x_ +
                  ((shifted.x() >> block_shift_) - min_block_.x())];
  }
  return sum;
}

void PrecomputationGrid2D::SumValuesOverOffsets(const std::vector<Eigen::Array2i>& cells,
                                                const Eigen::Array2i& cells_min,
                                                const Eigen::Array2i& cells_max,
                                                const Eigen::Array2i& first, int step, int num_x,
                                                int num_y, long* sums) const {
  assert(step > 0 && num_x >= 0 && num_y >= 0);
  if (num_x == 0 || num_y == 0) return;
  // A step of whole blocks moves every cell by the same number of blocks (floor division by
  // a power of two), so one block index per point serves all the offsets.
  const bool whole_blocks = (step & ((1 << block_shift_) - 1)) == 0;
  const Eigen::Array2i low = cells_min + first;
  const Eigen::Array2i high = cells_max + first + step * Eigen::Array2i(num_x - 1, num_y - 1);
  const bool on_grid = (low.x() >> block_shift_) >= min_block_.x() &&
                       (low.y() >> block_shift_) >= min_block_.y() &&
                       (high.x() >> block_shift_) < min_block_.x() + size_x_ &&
                       (high.y() >> block_shift_) < min_block_.y() + size_y_;
  // Per offset: steps of part blocks, and more rows than the passes below are written for (6,
  // local SLAM's wide search; a full-submap search's coarsest level can have more).
  if (!whole_blocks || num_y > 6) {
    for (int i = 0; i < num_x; ++i) {
      for (int j = 0; j < num_y; ++j) {
        sums[i * num_y + j] =
            SumValues(cells, cells_min, cells_max, first + step * Eigen::Array2i(i, j));
      }
    }
    return;
  }
  const int block_step = step >> block_shift_;
  const long row_step = static_cast<long>(block_step) * size_x_;
  // Columns first_column .. + kColumns - 1 of offsets (every j of each) per pass over the
  // points, their sums in registers. Checked: where the lattice reaches off the stored area,
  // a point whose offsets do not all land on it adds 0 for those that miss (as GetValue);
  // the others take the unchecked path, as on the stored area.
  const auto pass = [&](auto num_columns, auto num_rows, auto checked, int first_column) {
    constexpr int kColumns = decltype(num_columns)::value;
    constexpr int kRows = decltype(num_rows)::value;
    constexpr bool kChecked = decltype(checked)::value;
    long pass_sums[kColumns][kRows] = {};
    for (const Eigen::Array2i& cell : cells) {
      const Eigen::Array2i shifted = cell + first;
      const int x = (shifted.x() >> block_shift_) - min_block_.x() + first_column * block_step;
      const int y = (shifted.y() >> block_shift_) - min_block_.y();
      if (!kChecked || (x >= 0 && y >= 0 && x + (kColumns - 1) * block_step < size_x_ &&
                        y + (kRows - 1) * block_step < size_y_)) {
        const uint8_t* const value = values_.data() + static_cast<long>(y) * size_x_ + x;
        for (int i = 0; i < kColumns; ++i) {
          for (int j = 0; j < kRows; ++j) pass_sums[i][j] += value[i * block_step + j * row_step];
        }
        continue;
      }
      for (int i = 0; i < kColumns; ++i) {
        for (int j = 0; j < kRows; ++j) {
          const int xi = x + i * block_step;
          const int yj = y + j * block_step;
          if (xi < 0 || yj < 0 || xi >= size_x_ || yj >= size_y_) continue;
          pass_sums[i][j] += values_[static_cast<size_t>(yj) * size_x_ + xi];
        }
      }
    }
    for (int i = 0; i < kColumns; ++i) {
      std::copy_n(pass_sums[i], kRows, sums + (first_column + i) * num_y);
    }
  };
  const auto dispatch = [&](auto checked) {
    using One = std::integral_constant<int, 1>;
    using Two = std::integral_constant<int, 2>;
    // A branch and bound expansion's four children in one pass.
    if (num_x == 2 && num_y == 2) {
      pass(Two(), Two(), checked, 0);
      return;
    }
    for (int i = 0; i < num_x; ++i) {
      switch (num_y) {
        case 1:
          pass(One(), One(), checked, i);
          break;
        case 2:
          pass(One(), Two(), checked, i);
          break;
        case 3:
          pass(One(), std::integral_constant<int, 3>(), checked, i);
          break;
        case 4:
          pass(One(), std::integral_constant<int, 4>(), checked, i);
          break;
        case 5:
          pass(One(), std::integral_constant<int, 5>(), checked, i);
          break;
        case 6:
          pass(One(), std::integral_constant<int, 6>(), checked, i);
          break;
      }
    }
  };
  if (on_grid) {
    dispatch(std::false_type());
  } else {
    dispatch(std::true_type());
  }
}

PrecomputationGridStack2D::PrecomputationGridStack2D(const ProbabilityGrid& grid, int max_depth,
                                                     PrecomputationBuffers* buffers)
    : PrecomputationGridStack2D(grid, WholeGrid(grid), kMinProbability, max_depth, buffers) {}

PrecomputationGridStack2D::PrecomputationGridStack2D(const ProbabilityGrid& grid,
                                                     const CellBox& box, float unknown_probability,
                                                     int max_depth, PrecomputationBuffers* buffers)
    : PrecomputationGridStack2D(grid, box, unknown_probability, max_depth,
                                CellBox{Eigen::Array2i::Zero(), box.num_x_cells, box.num_y_cells},
                                buffers) {}

PrecomputationGridStack2D::PrecomputationGridStack2D(const ProbabilityGrid& grid,
                                                     const CellBox& box, float unknown_probability,
                                                     int max_depth, const CellBox& reads,
                                                     PrecomputationBuffers* buffers) {
  assert(max_depth >= 0 && box.num_x_cells >= 0 && box.num_y_cells >= 0);
  // The base cells the windows read at `reads` reach, at any depth: w - 1 past a window's
  // start for the exact depths, up to w + 2 blocks for the blocked ones (see the header); 2 w
  // covers both. Started on a block boundary of the deepest level, so that the blocks are the
  // same as over the whole box.
  const int reach = 2 << max_depth;
  const int block = 1 << std::max(0, max_depth - kExactDepths);
  CellBox stored;
  int stored_max[2];
  for (int axis = 0; axis < 2; ++axis) {
    const int size = axis == 0 ? box.num_x_cells : box.num_y_cells;
    const int read_size = axis == 0 ? reads.num_x_cells : reads.num_y_cells;
    // Floor to a multiple of `block` (>= 0 here).
    const int min = std::clamp(reads.min_cell[axis], 0, size) / block * block;
    stored.min_cell[axis] = min;
    stored_max[axis] = std::clamp(reads.min_cell[axis] + read_size - 1 + reach, min - 1, size - 1);
  }
  stored.num_x_cells = stored_max[0] - stored.min_cell.x() + 1;
  stored.num_y_cells = stored_max[1] - stored.min_cell.y() + 1;
  // Reserved: the levels are read in place (PlaneView) while the next one is built.
  grids_.reserve(max_depth + 1);
  grids_.push_back(PrecomputationGrid2D(
      grid, box, stored, unknown_probability,
      buffers != nullptr ? buffers->quantisation_table() : MakeQuantisationTable(),
      TakeBuffer(buffers, static_cast<size_t>(stored.num_x_cells) * stored.num_y_cells)));
  const auto view = [](const PrecomputationGrid2D& level) {
    return PlaneView{level.min_block_, level.size_x_, level.size_y_, level.values_.data()};
  };
  // Block maxima for the blocked depths, halved from the base grid one depth after another.
  Plane blocks;
  for (int depth = 1; depth <= max_depth; ++depth) {
    const int width = 1 << depth;
    Plane level;
    int block_shift = 0;
    if (depth <= kExactDepths) {
      // The window of w is two windows of w / 2 (the previous depth, exact), side by side.
      level = MaxOfStrided(view(grids_.back()), 2, width / 2, buffers);
    } else {
      block_shift = depth - kExactDepths;
      const bool first_blocked = depth == kExactDepths + 1;
      Plane halved = HalveByMax(first_blocked ? view(grids_.front()) : View(blocks), buffers);
      GiveBuffer(buffers, std::move(blocks.values));
      blocks = std::move(halved);
      // A window of w starting anywhere in a block reaches this many blocks.
      const int block = 1 << block_shift;
      level = MaxOfStrided(View(blocks), (width - 1 + block - 1) / block + 1, 1, buffers);
    }
    grids_.push_back(PrecomputationGrid2D(width, block_shift, level.min, level.size_x, level.size_y,
                                          std::move(level.values)));
  }
  GiveBuffer(buffers, std::move(blocks.values));
}

void PrecomputationGridStack2D::ReleaseInto(PrecomputationBuffers* buffers) {
  for (PrecomputationGrid2D& grid : grids_) buffers->Give(std::move(grid.values_));
  grids_.clear();
}

size_t PrecomputationGridStack2D::bytes() const {
  size_t total = 0;
  for (const auto& grid : grids_) total += grid.bytes();
  return total;
}

}  // namespace mapping
}  // namespace fusemap
