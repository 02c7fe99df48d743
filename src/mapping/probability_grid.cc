#include "fusemap/mapping/probability_grid.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <utility>

namespace fusemap {
namespace mapping {
namespace {
constexpr int kGrowMarginCells = 4;
}  // namespace

constexpr int64_t ProbabilityGrid::kMaxCells;

ProbabilityGrid::ProbabilityGrid(const MapLimits& limits)
    : limits_(limits),
      cells_(static_cast<size_t>(limits.num_x_cells) * limits.num_y_cells, kUnknownValue) {
  assert(limits.num_x_cells >= 0 && limits.num_y_cells >= 0 && limits.resolution_m > 0);
}

ProbabilityGrid::ProbabilityGrid(const MapLimits& limits, std::vector<uint16_t> cells)
    : limits_(limits), cells_(std::move(cells)) {
  assert(limits.num_x_cells >= 0 && limits.num_y_cells >= 0 && limits.resolution_m > 0);
  assert(cells_.size() == static_cast<size_t>(limits.num_x_cells) * limits.num_y_cells);
  // Each row's first and last known cell bound the row (a wide search builds grids of
  // millions of cells, most of them known).
  for (int y = 0; y < limits_.num_y_cells; ++y) {
    const uint16_t* const row = cells_.data() + limits_.FlatIndex(Eigen::Array2i(0, y));
    int first = 0;
    while (first < limits_.num_x_cells && row[first] == kUnknownValue) ++first;
    if (first == limits_.num_x_cells) continue;
    int last = limits_.num_x_cells - 1;
    while (row[last] == kUnknownValue) --last;
    ExtendKnownBounds(Eigen::Array2i(first, y));
    ExtendKnownBounds(Eigen::Array2i(last, y));
  }
}

float ProbabilityGrid::GetProbability(const Eigen::Array2i& cell) const {
  return GetProbabilityOr(cell, kMinProbability);
}

float ProbabilityGrid::GetProbabilityOr(const Eigen::Array2i& cell,
                                        float unknown_probability) const {
  if (!limits_.Contains(cell)) return unknown_probability;
  const uint16_t value = cells_[limits_.FlatIndex(cell)] & static_cast<uint16_t>(~kUpdateMarker);
  return value == kUnknownValue ? unknown_probability : ValueToProbability(value);
}

uint16_t ProbabilityGrid::GetValue(const Eigen::Array2i& cell) const {
  if (!limits_.Contains(cell)) return kUnknownValue;
  return cells_[limits_.FlatIndex(cell)] & static_cast<uint16_t>(~kUpdateMarker);
}

bool ProbabilityGrid::IsKnown(const Eigen::Array2i& cell) const {
  return GetValue(cell) != kUnknownValue;
}

void ProbabilityGrid::SetProbability(const Eigen::Array2i& cell, float probability) {
  assert(limits_.Contains(cell));
  cells_[limits_.FlatIndex(cell)] = ProbabilityToValue(probability);
  ExtendKnownBounds(cell);
}

bool ProbabilityGrid::ApplyLookupTable(const Eigen::Array2i& cell,
                                       const std::vector<uint16_t>& table) {
  assert(limits_.Contains(cell));
  const int index = limits_.FlatIndex(cell);
  uint16_t& value = cells_[index];
  if (value & kUpdateMarker) return false;
  update_indices_.push_back(index);
  value = table[value];
  assert(value & kUpdateMarker);
  ExtendKnownBounds(cell);
  return true;
}

void ProbabilityGrid::FinishUpdate() {
  for (int index : update_indices_) cells_[index] &= static_cast<uint16_t>(~kUpdateMarker);
  update_indices_.clear();
}

std::optional<MapLimits> ProbabilityGrid::LimitsCovering(const MapLimits& limits,
                                                         const Eigen::Vector2f& min_m,
                                                         const Eigen::Vector2f& max_m) {
  if (!min_m.allFinite() || !max_m.allFinite()) return std::nullopt;
  MapLimits grown = limits;
  for (;;) {
    // In double cell units, so that no far point is ever cast to int.
    const Eigen::Array2d lo =
        ((min_m.cast<double>() - grown.origin_m) / grown.resolution_m).array().floor();
    const Eigen::Array2d hi =
        ((max_m.cast<double>() - grown.origin_m) / grown.resolution_m).array().floor();
    const bool low_x = lo.x() < kGrowMarginCells;
    const bool high_x = hi.x() >= grown.num_x_cells - kGrowMarginCells;
    const bool low_y = lo.y() < kGrowMarginCells;
    const bool high_y = hi.y() >= grown.num_y_cells - kGrowMarginCells;
    if (!low_x && !high_x && !low_y && !high_y) return grown;
    // Double only the axes that fall short, towards the side(s) that do: amortised O(1) per
    // cell, and a robot driving along x does not pay for a grid that also doubles along y
    // (outdoors, with 30 m rays, that was four times the area and most of local SLAM's time).
    const int add_x = low_x || high_x ? std::max(grown.num_x_cells, 2 * kGrowMarginCells) : 0;
    const int add_y = low_y || high_y ? std::max(grown.num_y_cells, 2 * kGrowMarginCells) : 0;
    const int64_t cells = (int64_t{grown.num_x_cells} + add_x) * (int64_t{grown.num_y_cells} + add_y);
    if (cells > kMaxCells) return std::nullopt;
    // Cells added below the origin: all of them on a side that alone falls short, half when
    // both do.
    const int below_x = low_x ? (high_x ? add_x / 2 : add_x) : 0;
    const int below_y = low_y ? (high_y ? add_y / 2 : add_y) : 0;
    grown.origin_m -= grown.resolution_m * Eigen::Vector2d(below_x, below_y);
    grown.num_x_cells += add_x;
    grown.num_y_cells += add_y;
  }
}

bool ProbabilityGrid::GrowLimits(const Eigen::Vector2f& point_m) { return GrowLimits(point_m, point_m); }

bool ProbabilityGrid::GrowLimits(const Eigen::Vector2f& min_m, const Eigen::Vector2f& max_m) {
  assert(update_indices_.empty() && "grow between updates only");
  const std::optional<MapLimits> grown = LimitsCovering(limits_, min_m, max_m);
  if (!grown) return false;
  if (grown->num_x_cells == limits_.num_x_cells && grown->num_y_cells == limits_.num_y_cells) {
    return true;
  }
  const Eigen::Array2i offset(
      static_cast<int>(std::lround((limits_.origin_m.x() - grown->origin_m.x()) / grown->resolution_m)),
      static_cast<int>(std::lround((limits_.origin_m.y() - grown->origin_m.y()) / grown->resolution_m)));
  std::vector<uint16_t> cells(static_cast<size_t>(grown->num_x_cells) * grown->num_y_cells,
                              kUnknownValue);
  for (int y = 0; y < limits_.num_y_cells; ++y) {
    for (int x = 0; x < limits_.num_x_cells; ++x) {
      cells[grown->FlatIndex(Eigen::Array2i(x, y) + offset)] =
          cells_[limits_.FlatIndex(Eigen::Array2i(x, y))];
    }
  }
  limits_ = *grown;
  cells_.swap(cells);
  known_min_ += offset;
  known_max_ += offset;
  return true;
}

bool ProbabilityGrid::ComputeKnownBounds(Eigen::Array2i* min_cell, Eigen::Array2i* max_cell) const {
  if (!any_known_) return false;
  *min_cell = known_min_;
  *max_cell = known_max_;
  return true;
}

ProbabilityGrid ProbabilityGrid::Cropped() const {
  Eigen::Array2i min_cell, max_cell;
  if (!ComputeKnownBounds(&min_cell, &max_cell)) return *this;
  MapLimits cropped = limits_;
  cropped.origin_m = limits_.origin_m + limits_.resolution_m * min_cell.cast<double>().matrix();
  cropped.num_x_cells = max_cell.x() - min_cell.x() + 1;
  cropped.num_y_cells = max_cell.y() - min_cell.y() + 1;
  ProbabilityGrid result(cropped);
  for (int y = 0; y < cropped.num_y_cells; ++y) {
    for (int x = 0; x < cropped.num_x_cells; ++x) {
      result.cells_[cropped.FlatIndex(Eigen::Array2i(x, y))] =
          cells_[limits_.FlatIndex(Eigen::Array2i(x, y) + min_cell)];
    }
  }
  result.any_known_ = true;
  result.known_min_ = Eigen::Array2i::Zero();
  result.known_max_ = max_cell - min_cell;
  return result;
}

}  // namespace mapping
}  // namespace fusemap
