#include "fusemap/pose_graph/overlapping_submaps_trimmer_2d.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <memory>
#include <unordered_map>

#include "fusemap/mapping/probability_values.h"

namespace fusemap {
namespace pose_graph {
namespace {

// Map cells as (x, y) indices at the binning resolution.
std::int64_t FloorToCell(double coordinate_m, double resolution_m) {
  return static_cast<std::int64_t>(std::floor(coordinate_m / resolution_m));
}

// Per map cell, how many of the submaps counted so far know it (up to fresh_submaps_count). A
// byte per cell, in tiles of 64 x 64 cells made only where some submap knows a cell: a campus
// holds tens of millions of cells in its bounding box, and a hash map entry per known cell took
// freiburg-campus' run with the trimmer to 595 MB of RSS (334 MB with the tiles).
class KnowerCounts {
 public:
  static constexpr int kTileBits = 6;
  static constexpr int kTileSize = 1 << kTileBits;

  // A cell's key orders cells tile by tile, so that sorted keys visit each tile once. (`>>` of
  // a negative index is an arithmetic shift with GCC, as C++20 defines it: floor division.)
  static std::uint64_t Key(std::int64_t x, std::int64_t y) {
    const std::uint64_t tile_x = static_cast<std::uint32_t>(x >> kTileBits) & 0xffffff;
    const std::uint64_t tile_y = static_cast<std::uint32_t>(y >> kTileBits) & 0xffffff;
    const std::uint64_t in_tile =
        static_cast<std::uint64_t>(((y & (kTileSize - 1)) << kTileBits) | (x & (kTileSize - 1)));
    return (tile_x << 40) | (tile_y << 16) | in_tile;
  }

  std::uint8_t& At(std::uint64_t key) {
    const std::uint64_t tile_key = key >> 16;
    if (tile_ == nullptr || tile_key != tile_key_) {
      std::unique_ptr<Tile>& tile = tiles_[tile_key];
      if (!tile) tile = std::make_unique<Tile>();  // zeroed
      tile_ = tile.get();
      tile_key_ = tile_key;
    }
    return (*tile_)[key & 0xffff];
  }

 private:
  using Tile = std::array<std::uint8_t, kTileSize * kTileSize>;
  std::unordered_map<std::uint64_t, std::unique_ptr<Tile>> tiles_;
  Tile* tile_ = nullptr;  // the last tile used, and its key
  std::uint64_t tile_key_ = 0;
};

}  // namespace

void OverlappingSubmapsTrimmerOptions2D::Check(common::OptionChecker* check) const {
  check->Require(fresh_submaps_count >= 0 && fresh_submaps_count <= kMaxFreshSubmaps,
                 "fresh_submaps_count", "must be in [0, " + std::to_string(kMaxFreshSubmaps) + "]");
  check->Require(
      min_probability_margin >= 0.0 && min_probability_margin < 0.5 - mapping::kMinProbability,
      "min_probability_margin", "must be in [0, 0.4): no cell's probability is further from 0.5");
  check->Require(min_covered_area_m2 >= 0.0 && std::isfinite(min_covered_area_m2),
                 "min_covered_area_m2", "must be >= 0");
  check->Require(min_added_submaps_count >= 1, "min_added_submaps_count", "must be >= 1");
}

bool OverlappingSubmapsTrimmerOptions2D::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

OverlappingSubmapsTrimmerOptions2D ParseOverlappingSubmapsTrimmerOptions2D(
    common::ConfigReader& reader) {
  OverlappingSubmapsTrimmerOptions2D options;
  reader.Get("fresh_submaps_count", &options.fresh_submaps_count);
  reader.Get("min_probability_margin", &options.min_probability_margin);
  reader.Get("min_covered_area_m2", &options.min_covered_area_m2);
  reader.Get("min_added_submaps_count", &options.min_added_submaps_count);
  reader.CheckOptions(options);
  return options;
}

std::vector<int> FindSubmapsToTrim(const std::vector<PlacedSubmap2D>& submaps,
                                   const OverlappingSubmapsTrimmerOptions2D& options) {
  assert(options.enabled());
  if (submaps.empty()) return {};
  const int keep = options.fresh_submaps_count;
  double resolution_m = 0.0;  // the newest grid's

  // Newest first: a submap is among a cell's fresh ones where fewer than `keep` newer submaps
  // know the cell.
  KnowerCounts newer_knowers;
  std::vector<int> trim;
  std::vector<std::uint64_t> known;  // the map cells the submap knows, each once
  for (size_t i = submaps.size(); i-- > 0;) {
    assert(i == 0 || submaps[i - 1].submap < submaps[i].submap);
    known.clear();
    {
      const std::shared_ptr<const mapping::ProbabilityGrid> held_grid = submaps[i].grid();
      const mapping::ProbabilityGrid& grid = *held_grid;
      const mapping::MapLimits& limits = grid.limits();
      if (resolution_m == 0.0) resolution_m = limits.resolution_m;
      Eigen::Array2i min_cell, max_cell;
      if (grid.ComputeKnownBounds(&min_cell, &max_cell)) {
        for (int y = min_cell.y(); y <= max_cell.y(); ++y) {
          for (int x = min_cell.x(); x <= max_cell.x(); ++x) {
            const Eigen::Array2i cell(x, y);
            if (!grid.IsKnown(cell) ||
                std::abs(grid.GetProbability(cell) - 0.5f) < options.min_probability_margin) {
              continue;
            }
            const Eigen::Vector2d point_m = submaps[i].T_map_grid * limits.GetCellCenter(cell);
            known.push_back(KnowerCounts::Key(FloorToCell(point_m.x(), resolution_m),
                                              FloorToCell(point_m.y(), resolution_m)));
          }
        }
      }
    }
    // A rotated grid can put two of its cells into one map cell; count the submap once.
    std::sort(known.begin(), known.end());
    known.erase(std::unique(known.begin(), known.end()), known.end());
    long kept_cells = 0;
    for (const std::uint64_t key : known) {
      std::uint8_t& count = newer_knowers.At(key);
      if (count < keep) {
        ++kept_cells;
        ++count;
      }
    }
    if (kept_cells * resolution_m * resolution_m < options.min_covered_area_m2) {
      trim.push_back(submaps[i].submap);
    }
  }
  std::reverse(trim.begin(), trim.end());
  return trim;
}

}  // namespace pose_graph
}  // namespace fusemap
