#include "fusemap/mapping/range_data_inserter_2d.h"

#include <cassert>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace fusemap {
namespace mapping {
namespace {

// Applies `table` to every cell the segment begin->end passes through, in order, using the
// exact grid traversal of Amanatides & Woo 1987 ("A Fast Voxel Traversal Algorithm"). The
// step count is fixed by the cell distance, so the walk always ends in end's cell even when
// rounding makes the crossing comparisons ambiguous. The end cell is included only if asked.
void CastRay(const Eigen::Vector2f& begin, const Eigen::Vector2f& end, bool include_end,
             const std::vector<uint16_t>& table, ProbabilityGrid* grid) {
  const MapLimits& limits = grid->limits();
  const Eigen::Array2i begin_cell = limits.GetCellIndex(begin);
  const Eigen::Array2i end_cell = limits.GetCellIndex(end);
  const Eigen::Array2i delta = end_cell - begin_cell;
  const int num_steps = std::abs(delta.x()) + std::abs(delta.y());
  const Eigen::Array2i step(delta.x() > 0 ? 1 : -1, delta.y() > 0 ? 1 : -1);

  // Position in cell units relative to the grid origin.
  // Same arithmetic as MapLimits::GetCellIndex, so begin lies inside begin_cell.
  const double res = limits.resolution_m;
  const double bx = (begin.x() - limits.origin_m.x()) / res;
  const double by = (begin.y() - limits.origin_m.y()) / res;
  const double dx = (end.x() - limits.origin_m.x()) / res - bx;
  const double dy = (end.y() - limits.origin_m.y()) / res - by;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // Ray parameter t in [0, 1] at which the next vertical / horizontal cell boundary is crossed.
  const double t_delta_x = delta.x() != 0 ? std::abs(1.0 / dx) : kInf;
  const double t_delta_y = delta.y() != 0 ? std::abs(1.0 / dy) : kInf;
  double t_max_x =
      delta.x() != 0 ? ((begin_cell.x() + (step.x() > 0 ? 1 : 0)) - bx) / dx : kInf;
  double t_max_y =
      delta.y() != 0 ? ((begin_cell.y() + (step.y() > 0 ? 1 : 0)) - by) / dy : kInf;

  Eigen::Array2i cell = begin_cell;
  int remaining_x = std::abs(delta.x());
  int remaining_y = std::abs(delta.y());
  for (int i = 0; i < num_steps; ++i) {
    grid->ApplyLookupTable(cell, table);
    if (remaining_y == 0 || (remaining_x > 0 && t_max_x < t_max_y)) {
      cell.x() += step.x();
      t_max_x += t_delta_x;
      --remaining_x;
    } else {
      cell.y() += step.y();
      t_max_y += t_delta_y;
      --remaining_y;
    }
  }
  assert((cell == end_cell).all());
  if (include_end) grid->ApplyLookupTable(cell, table);
}

}  // namespace

void ProbabilityGridRangeDataInserterOptions::Check(common::OptionChecker* check) const {
  check->Require(hit_probability > 0.5f && hit_probability <= kMaxProbability, "hit_probability",
                 "must lie in (0.5, 0.9]");
  check->Require(miss_probability >= kMinProbability && miss_probability < 0.5f,
                 "miss_probability", "must lie in [0.1, 0.5)");
}

bool ProbabilityGridRangeDataInserterOptions::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

ProbabilityGridRangeDataInserterOptions ParseProbabilityGridRangeDataInserterOptions(
    common::ConfigReader& reader) {
  ProbabilityGridRangeDataInserterOptions options;
  reader.Get("hit_probability", &options.hit_probability);
  reader.Get("miss_probability", &options.miss_probability);
  reader.Get("insert_free_space", &options.insert_free_space);
  reader.CheckOptions(options);
  return options;
}

RangeDataInserter2D::RangeDataInserter2D(const ProbabilityGridRangeDataInserterOptions& options)
    : options_(options),
      hit_table_(ComputeLookupTableToApplyOdds(Odds(options.hit_probability))),
      miss_table_(ComputeLookupTableToApplyOdds(Odds(options.miss_probability))) {
  std::string error;
  assert(options.IsValid(&error));
}

bool RangeDataBounds(const sensor::RangeData& range_data, Eigen::Vector2f* min_m, Eigen::Vector2f* max_m) {
  Eigen::Vector2f lo = range_data.origin;
  Eigen::Vector2f hi = range_data.origin;
  for (const auto* points : {&range_data.returns, &range_data.misses}) {
    for (const Eigen::Vector2f& point : *points) {
      lo = lo.cwiseMin(point);
      hi = hi.cwiseMax(point);
    }
  }
  // cwiseMin/Max may drop a NaN, so check the points themselves.
  bool finite = range_data.origin.allFinite();
  for (const auto* points : {&range_data.returns, &range_data.misses}) {
    for (const Eigen::Vector2f& point : *points) finite = finite && point.allFinite();
  }
  *min_m = lo;
  *max_m = hi;
  return finite;
}

bool RangeDataInserter2D::Insert(const sensor::RangeData& range_data,
                                 ProbabilityGrid* grid) const {
  Eigen::Vector2f min_m, max_m;
  if (!RangeDataBounds(range_data, &min_m, &max_m) || !grid->GrowLimits(min_m, max_m)) return false;

  const MapLimits& limits = grid->limits();
  for (const Eigen::Vector2f& point : range_data.returns) {
    grid->ApplyLookupTable(limits.GetCellIndex(point), hit_table_);
  }
  if (options_.insert_free_space) {
    for (const Eigen::Vector2f& point : range_data.returns) {
      CastRay(range_data.origin, point, /*include_end=*/false, miss_table_, grid);
    }
    for (const Eigen::Vector2f& point : range_data.misses) {
      CastRay(range_data.origin, point, /*include_end=*/true, miss_table_, grid);
    }
  }
  grid->FinishUpdate();
  return true;
}

}  // namespace mapping
}  // namespace fusemap
