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
  // In double cell units, so that no far point is ever cast to int.
  const auto inside = [&](const MapLimits& l) {
    const Eigen::Array2d lo = ((min_m.cast<double>() - l.origin_m) / l.resolution_m).array().floor();
    const Eigen::Array2d hi = ((max_m.cast<double>() - l.origin_m) / l.resolution_m).array().floor();
    return lo.x() >= kGrowMarginCells && lo.y() >= kGrowMarginCells &&
           hi.x() < l.num_x_cells - kGrowMarginCells && hi.y() < l.num_y_cells - kGrowMarginCells;
  };
  MapLimits grown = limits;
  while (!inside(grown)) {
    // Double about the centre so growth is symmetric and amortised O(1) per cell.
    const int add_x = std::max(grown.num_x_cells, 2 * kGrowMarginCells);
    const int add_y = std::max(grown.num_y_cells, 2 * kGrowMarginCells);
    const int64_t cells = (int64_t{grown.num_x_cells} + add_x) * (int64_t{grown.num_y_cells} + add_y);
    if (cells > kMaxCells) return std::nullopt;
    grown.origin_m -= grown.resolution_m * Eigen::Vector2d(add_x / 2, add_y / 2);
    grown.num_x_cells += add_x;
    grown.num_y_cells += add_y;
  }
  return grown;
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
  return true;
}

bool ProbabilityGrid::ComputeKnownBounds(Eigen::Array2i* min_cell, Eigen::Array2i* max_cell) const {
  bool any = false;
  for (int y = 0; y < limits_.num_y_cells; ++y) {
    for (int x = 0; x < limits_.num_x_cells; ++x) {
      if (cells_[limits_.FlatIndex(Eigen::Array2i(x, y))] == kUnknownValue) continue;
      const Eigen::Array2i c(x, y);
      if (!any) {
        *min_cell = c;
        *max_cell = c;
        any = true;
      } else {
        *min_cell = min_cell->min(c);
        *max_cell = max_cell->max(c);
      }
    }
  }
  return any;
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
  return result;
}

}  // namespace mapping
}  // namespace fusemap
