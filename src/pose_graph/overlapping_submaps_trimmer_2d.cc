#include "fusemap/pose_graph/overlapping_submaps_trimmer_2d.h"

#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "fusemap/mapping/probability_values.h"

namespace fusemap {
namespace pose_graph {
namespace {

// The newest submaps seen in one map cell, as a ring (submaps arrive oldest first).
struct FreshSubmaps {
  std::array<int, OverlappingSubmapsTrimmerOptions2D::kMaxFreshSubmaps> ids{};
  int count = 0;
  int next = 0;
  int newest = -1;
};

std::uint64_t CellKey(const Eigen::Vector2d& point_m, double resolution_m) {
  const auto x = static_cast<std::int32_t>(std::floor(point_m.x() / resolution_m));
  const auto y = static_cast<std::int32_t>(std::floor(point_m.y() / resolution_m));
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(x)) << 32) |
         static_cast<std::uint32_t>(y);
}

}  // namespace

void OverlappingSubmapsTrimmerOptions2D::Check(common::OptionChecker* check) const {
  check->Require(fresh_submaps_count >= 0 && fresh_submaps_count <= kMaxFreshSubmaps,
                 "fresh_submaps_count",
                 "must be in [0, " + std::to_string(kMaxFreshSubmaps) + "]");
  check->Require(min_probability_margin >= 0.0 &&
                     min_probability_margin < 0.5 - mapping::kMinProbability,
                 "min_probability_margin",
                 "must be in [0, 0.4): no cell's probability is further from 0.5");
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
  double resolution_m = 0.0;  // the first grid's
  const int keep = options.fresh_submaps_count;

  std::unordered_map<std::uint64_t, FreshSubmaps> cells;
  for (size_t i = 0; i < submaps.size(); ++i) {
    assert(i == 0 || submaps[i - 1].submap < submaps[i].submap);
    const std::shared_ptr<const mapping::ProbabilityGrid> held_grid = submaps[i].grid();
    const mapping::ProbabilityGrid& grid = *held_grid;
    const mapping::MapLimits& limits = grid.limits();
    if (i == 0) resolution_m = limits.resolution_m;
    Eigen::Array2i min_cell, max_cell;
    if (!grid.ComputeKnownBounds(&min_cell, &max_cell)) continue;
    for (int y = min_cell.y(); y <= max_cell.y(); ++y) {
      for (int x = min_cell.x(); x <= max_cell.x(); ++x) {
        const Eigen::Array2i cell(x, y);
        if (!grid.IsKnown(cell) ||
            std::abs(grid.GetProbability(cell) - 0.5f) < options.min_probability_margin) {
          continue;
        }
        const Eigen::Vector2d point_m = submaps[i].T_map_grid * limits.GetCellCenter(cell);
        FreshSubmaps& fresh = cells[CellKey(point_m, resolution_m)];
        // A rotated grid can put two of its cells into one map cell; count the submap once.
        if (fresh.newest == submaps[i].submap) continue;
        fresh.newest = submaps[i].submap;
        fresh.ids[fresh.next] = static_cast<int>(i);
        fresh.next = (fresh.next + 1) % keep;
        if (fresh.count < keep) ++fresh.count;
      }
    }
  }

  std::vector<long> kept_cells(submaps.size(), 0);
  for (const auto& [key, fresh] : cells) {
    for (int k = 0; k < fresh.count; ++k) ++kept_cells[fresh.ids[k]];
  }
  const double cell_area_m2 = resolution_m * resolution_m;
  std::vector<int> trim;
  for (size_t i = 0; i < submaps.size(); ++i) {
    if (kept_cells[i] * cell_area_m2 < options.min_covered_area_m2) {
      trim.push_back(submaps[i].submap);
    }
  }
  return trim;
}

}  // namespace pose_graph
}  // namespace fusemap
