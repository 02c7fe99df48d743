#include "fusemap/mapping/grid_image.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace fusemap {
namespace mapping {
namespace {

struct Box {
  Eigen::Vector2d min = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d max = Eigen::Vector2d::Constant(-std::numeric_limits<double>::infinity());
  void Extend(const Eigen::Vector2d& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  bool empty() const { return !(min.x() <= max.x()); }
};

// Map-frame bounding box of the known cells of `grid`; empty if none is known.
Box KnownBoxInMap(const common::Rigid2d& T_map_grid, const ProbabilityGrid& grid) {
  Box box;
  Eigen::Array2i min_cell, max_cell;
  if (!grid.ComputeKnownBounds(&min_cell, &max_cell)) return box;
  const MapLimits& limits = grid.limits();
  const Eigen::Vector2d lo = limits.origin_m + limits.resolution_m * min_cell.cast<double>().matrix();
  const Eigen::Vector2d hi =
      limits.origin_m + limits.resolution_m * (max_cell + 1).cast<double>().matrix();
  for (const Eigen::Vector2d& corner : {lo, hi, Eigen::Vector2d(lo.x(), hi.y()),
                                        Eigen::Vector2d(hi.x(), lo.y())}) {
    box.Extend(T_map_grid * corner);
  }
  return box;
}

}  // namespace

uint8_t ProbabilityToPixel(float probability) {
  if (probability < kFreeBelowProbability) return kFreePixel;
  if (probability > kOccupiedAboveProbability) return kOccupiedPixel;
  return static_cast<uint8_t>(std::lround(255.f * (1.f - probability)));
}

GridImage RenderMap(const std::vector<PlacedGrid>& grids, double resolution_m) {
  std::vector<GridSource> sources;
  sources.reserve(grids.size());
  for (const PlacedGrid& placed : grids) {
    // Not owned: the caller holds the grid for the whole call.
    const ProbabilityGrid* grid = placed.second;
    sources.push_back({placed.first, [grid] {
                         return std::shared_ptr<const ProbabilityGrid>(std::shared_ptr<void>(), grid);
                       }});
  }
  return RenderMap(sources, resolution_m);
}

GridImage RenderMap(const std::vector<GridSource>& grids, double resolution_m) {
  assert(resolution_m > 0.0);
  GridImage image;
  image.resolution_m = resolution_m;
  std::vector<Box> boxes;
  Box total;
  for (const GridSource& source : grids) {
    boxes.push_back(KnownBoxInMap(source.T_map_grid, *source.fetch()));
    if (boxes.back().empty()) continue;
    total.Extend(boxes.back().min);
    total.Extend(boxes.back().max);
  }
  if (total.empty()) return image;

  // Not snapped to a global lattice: for a single unrotated grid at its own resolution this
  // puts pixel centres on cell centres, so nearest-cell sampling is exact.
  const Eigen::Vector2d corner = total.min;
  image.origin_m = corner;
  image.width = static_cast<int>(std::ceil((total.max.x() - corner.x()) / resolution_m - 1e-9));
  image.height = static_cast<int>(std::ceil((total.max.y() - corner.y()) / resolution_m - 1e-9));
  image.width = std::max(image.width, 1);
  image.height = std::max(image.height, 1);

  const size_t num_pixels = static_cast<size_t>(image.width) * image.height;
  // The most confident (|p - 0.5|) cell value so far, kUnknownValue while no grid knows the
  // pixel. Raw 2-byte values rather than floats: a campus-sized map has tens of millions of
  // pixels.
  std::vector<uint16_t> best(num_pixels, kUnknownValue);
  for (size_t g = 0; g < grids.size(); ++g) {
    if (boxes[g].empty()) continue;
    const std::shared_ptr<const ProbabilityGrid> held_grid = grids[g].fetch();
    const ProbabilityGrid& grid = *held_grid;
    const common::Rigid2d T_grid_map = grids[g].T_map_grid.inverse();
    const int col_begin =
        std::max(0, static_cast<int>(std::floor((boxes[g].min.x() - corner.x()) / resolution_m)));
    const int col_end = std::min(
        image.width, static_cast<int>(std::ceil((boxes[g].max.x() - corner.x()) / resolution_m)));
    const int y_begin =
        std::max(0, static_cast<int>(std::floor((boxes[g].min.y() - corner.y()) / resolution_m)));
    const int y_end = std::min(
        image.height, static_cast<int>(std::ceil((boxes[g].max.y() - corner.y()) / resolution_m)));
    for (int y_index = y_begin; y_index < y_end; ++y_index) {
      const int row = image.height - 1 - y_index;
      for (int col = col_begin; col < col_end; ++col) {
        const Eigen::Vector2d centre_in_map =
            corner + resolution_m * Eigen::Vector2d(col + 0.5, y_index + 0.5);
        const Eigen::Array2i cell =
            grid.limits().GetCellIndex((T_grid_map * centre_in_map).cast<float>());
        const uint16_t value = grid.GetValue(cell);
        if (value == kUnknownValue) continue;
        const size_t index = static_cast<size_t>(row) * image.width + col;
        if (best[index] == kUnknownValue ||
            std::abs(ValueToProbability(value) - 0.5f) >
                std::abs(ValueToProbability(best[index]) - 0.5f)) {
          best[index] = value;
        }
      }
    }
  }

  image.pixels.resize(num_pixels);
  for (size_t i = 0; i < num_pixels; ++i) {
    image.pixels[i] =
        best[i] == kUnknownValue ? kUnknownPixel : ProbabilityToPixel(ValueToProbability(best[i]));
  }
  return image;
}

GridImage RenderGrid(const ProbabilityGrid& grid) {
  return RenderMap({PlacedGrid(common::Rigid2d::Identity(), &grid)}, grid.limits().resolution_m);
}

}  // namespace mapping
}  // namespace fusemap
