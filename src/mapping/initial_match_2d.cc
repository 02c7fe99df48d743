#include "fusemap/mapping/scan_matching/initial_match_2d.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

namespace fusemap {
namespace mapping {

InitialMatchOptions2D::InitialMatchOptions2D() {
  // Local SLAM's motion between scans, not loop closure's drift: a smaller window, a few times
  // the real-time one (config/default.yaml).
  fast_correlative_scan_matcher.linear_search_window_m = 0.5;
  fast_correlative_scan_matcher.angular_search_window_rad = 0.5;
  fast_correlative_scan_matcher.branch_and_bound_depth = 2;  // see config/default.yaml
  // Low: the real-time match started from the answer decides whether it is taken.
  fast_correlative_scan_matcher.min_score = 0.2;
  // Of two offsets that score alike (a corridor), the nearer the prediction.
  fast_correlative_scan_matcher.translation_delta_cost_weight = 0.5;
}

void InitialMatchOptions2D::Check(common::OptionChecker* check) const {
  check->Require(matching_resolution_m >= 0.0, "matching_resolution_m", "must be >= 0");
  check->Require(unknown_probability >= kMinProbability && unknown_probability <= kMaxProbability,
                 "unknown_probability", "must be in [0.1, 0.9]");
  check->Require(unknown_padding_m >= 0.0, "unknown_padding_m", "must be >= 0");
  check->Require(min_score_gain >= 0.0 && min_score_gain <= 1.0, "min_score_gain",
                 "must be in [0, 1]");
  check->Require(near_linear_search_window_m >= 0.0, "near_linear_search_window_m",
                 "must be >= 0");
  check->Require(near_angular_search_window_rad >= 0.0 &&
                     near_angular_search_window_rad <= common::kPi,
                 "near_angular_search_window_rad", "must be in [0, pi]");
  check->Require(refresh_every_n_insertions >= 1, "refresh_every_n_insertions", "must be >= 1");
  check->Require(min_rescore_gain >= 0.0 && min_rescore_gain <= 1.0, "min_rescore_gain",
                 "must be in [0, 1]");
  // The matcher's keys sit in this stage's own mapping (see ParseInitialMatchOptions2D).
  fast_correlative_scan_matcher.Check(check);
}

bool InitialMatchOptions2D::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

InitialMatchOptions2D ParseInitialMatchOptions2D(common::ConfigReader& reader) {
  InitialMatchOptions2D options;
  reader.Get("enabled", &options.enabled);
  reader.Get("matching_resolution_m", &options.matching_resolution_m);
  reader.Get("unknown_probability", &options.unknown_probability);
  reader.Get("unknown_padding_m", &options.unknown_padding_m);
  reader.Get("min_score_gain", &options.min_score_gain);
  reader.Get("near_linear_search_window_m", &options.near_linear_search_window_m);
  reader.Get("near_angular_search_window_rad", &options.near_angular_search_window_rad);
  reader.Get("refresh_every_n_insertions", &options.refresh_every_n_insertions);
  reader.Get("only_at_window_edge", &options.only_at_window_edge);
  reader.Get("min_rescore_gain", &options.min_rescore_gain);
  // Read field by field, not with ParseFastCorrelativeScanMatcherOptions2D, so that absent
  // keys keep this stage's defaults rather than loop closure's.
  FastCorrelativeScanMatcherOptions2D& fast = options.fast_correlative_scan_matcher;
  reader.Get("linear_search_window_m", &fast.linear_search_window_m);
  reader.Get("angular_search_window_rad", &fast.angular_search_window_rad);
  reader.Get("branch_and_bound_depth", &fast.branch_and_bound_depth);
  reader.Get("min_score", &fast.min_score);
  reader.Get("translation_delta_cost_weight", &fast.translation_delta_cost_weight);
  reader.Get("rotation_delta_cost_weight", &fast.rotation_delta_cost_weight);
  reader.CheckOptions(options);
  return options;
}

namespace {

// Where MaxPoolGrid's result lies: `fine` is the known part of the grid (from known_min),
// `coarse` the result.
struct PoolLayout {
  Eigen::Array2i known_min;
  MapLimits fine;
  MapLimits coarse;
};

PoolLayout ComputePoolLayout(const ProbabilityGrid& grid, int factor, int pad_cells) {
  assert(factor >= 1 && pad_cells >= 0);
  PoolLayout layout;
  // The known part of `grid`, read in place (local SLAM's submap grows to several times it).
  layout.known_min = Eigen::Array2i::Zero();
  Eigen::Array2i known_max(grid.limits().num_x_cells - 1, grid.limits().num_y_cells - 1);
  grid.ComputeKnownBounds(&layout.known_min, &known_max);
  MapLimits& fine = layout.fine;
  fine = grid.limits();
  fine.origin_m += fine.resolution_m * layout.known_min.cast<double>().matrix();
  fine.num_x_cells = known_max.x() - layout.known_min.x() + 1;
  fine.num_y_cells = known_max.y() - layout.known_min.y() + 1;
  MapLimits& coarse = layout.coarse;
  coarse = fine;
  coarse.resolution_m = fine.resolution_m * factor;
  coarse.origin_m -= Eigen::Vector2d::Constant(pad_cells * coarse.resolution_m);
  coarse.num_x_cells = (fine.num_x_cells + factor - 1) / factor + 2 * pad_cells;
  coarse.num_y_cells = (fine.num_y_cells + factor - 1) / factor + 2 * pad_cells;
  return layout;
}

}  // namespace

ProbabilityGrid MaxPoolGrid(const ProbabilityGrid& grid, int factor, float unknown_probability,
                            int pad_cells) {
  const PoolLayout layout = ComputePoolLayout(grid, factor, pad_cells);
  const Eigen::Array2i& known_min = layout.known_min;
  const MapLimits& fine = layout.fine;
  const MapLimits& coarse = layout.coarse;
  // Cell values increase with probability and kUnknownValue is 0, so the maximum value is the
  // most likely occupied known cell, or unknown if none is known.
  std::vector<uint16_t> cells(static_cast<size_t>(coarse.num_x_cells) * coarse.num_y_cells,
                              kUnknownValue);
  // Rows read in place (as grid.GetValue): with a coarser matching_resolution_m this runs on
  // every wide search, over the whole known part of the submap. (At the submap's own
  // resolution InitialMatcher2D reads the submap itself and does not call this.)
  constexpr uint16_t kValueMask = static_cast<uint16_t>(~kUpdateMarker);
  for (int y = 0; y < fine.num_y_cells; ++y) {
    const uint16_t* const fine_row =
        grid.cells().data() + grid.limits().FlatIndex(Eigen::Array2i(0, y) + known_min);
    uint16_t* const coarse_row =
        cells.data() + coarse.FlatIndex(Eigen::Array2i(pad_cells, y / factor + pad_cells));
    for (int x = 0; x < fine.num_x_cells; ++x) {
      uint16_t& value = coarse_row[x / factor];
      value = std::max(value, static_cast<uint16_t>(fine_row[x] & kValueMask));
    }
  }
  if (unknown_probability > kMinProbability) {
    const uint16_t unknown_value = ProbabilityToValue(unknown_probability);
    for (uint16_t& value : cells) {
      if (value == kUnknownValue) value = unknown_value;
    }
  }
  return ProbabilityGrid(coarse, std::move(cells));
}

InitialMatcher2D::InitialMatcher2D(const InitialMatchOptions2D& options) : options_(options) {
  std::string error;
  assert(options_.IsValid(&error));
  (void)error;
}

namespace {

bool Contains(const CellBox& outer, const CellBox& inner) {
  return inner.num_x_cells <= 0 || inner.num_y_cells <= 0 ||
         ((inner.min_cell >= outer.min_cell).all() &&
          inner.min_cell.x() + inner.num_x_cells <= outer.min_cell.x() + outer.num_x_cells &&
          inner.min_cell.y() + inner.num_y_cells <= outer.min_cell.y() + outer.num_y_cells);
}

}  // namespace

bool InitialMatcher2D::Match(const std::shared_ptr<const Submap2D>& submap,
                             const common::Rigid2d& predicted, const sensor::PointCloud2d& cloud,
                             double* score, common::Rigid2d* pose, double min_fit) {
  assert(submap != nullptr && score != nullptr && pose != nullptr);
  FastCorrelativeScanMatcherOptions2D local;
  if (options_.min_score_gain > 0.0) {
    local.linear_search_window_m = options_.near_linear_search_window_m;
    local.angular_search_window_rad = options_.near_angular_search_window_rad;
    local.branch_and_bound_depth = options_.fast_correlative_scan_matcher.branch_and_bound_depth;
    local.translation_delta_cost_weight =
        options_.fast_correlative_scan_matcher.translation_delta_cost_weight;
    local.rotation_delta_cost_weight =
        options_.fast_correlative_scan_matcher.rotation_delta_cost_weight;
  }
  // The cells this search reads, of the grids laid out as `limits`.
  const auto cells_read = [&](const MapLimits& limits) {
    CellBox reads =
        CellsReadByMatch(limits, options_.fast_correlative_scan_matcher, predicted, cloud);
    if (options_.min_score_gain > 0.0) {
      const CellBox near = CellsReadByMatch(limits, local, predicted, cloud);
      const Eigen::Array2i min_cell = reads.min_cell.min(near.min_cell);
      const Eigen::Array2i end_cell =
          (reads.min_cell + Eigen::Array2i(reads.num_x_cells, reads.num_y_cells))
              .max(near.min_cell + Eigen::Array2i(near.num_x_cells, near.num_y_cells));
      reads = CellBox{min_cell, end_cell.x() - min_cell.x(), end_cell.y() - min_cell.y()};
    }
    return reads;
  };
  const bool same_submap = cached_submap_.lock() == submap;
  // The grids are built for the cells the search reads only (a few metres around the scan,
  // where an open hall's submap spans tens), so a search that reads others rebuilds them.
  if (matcher_ == nullptr || !same_submap ||
      submap->num_range_data() - cached_num_range_data_ >= options_.refresh_every_n_insertions ||
      !Contains(cached_reads_, cells_read(cached_limits_))) {
    const std::shared_ptr<const ProbabilityGrid> grid = submap->grid();
    const int factor = std::max(
        1, static_cast<int>(std::lround(options_.matching_resolution_m /
                                        grid->limits().resolution_m)));
    const double coarse_resolution_m = factor * grid->limits().resolution_m;
    const int pad_cells =
        options_.unknown_probability > kMinProbability
            ? static_cast<int>(std::ceil(options_.unknown_padding_m / coarse_resolution_m))
            : 0;
    if (matcher_ != nullptr) matcher_->ReleaseGridsInto(&buffers_);
    if (local_matcher_ != nullptr) local_matcher_->ReleaseGridsInto(&buffers_);
    // At the submap's own resolution (the default) the stacks are built from the submap's
    // grid in place: the same values as from MaxPoolGrid's copy, which cost as much as the
    // stacks themselves (orebro).
    std::optional<ProbabilityGrid> pooled;
    MapLimits limits;
    CellBox box;
    if (factor == 1) {
      const PoolLayout layout = ComputePoolLayout(*grid, 1, pad_cells);
      limits = layout.coarse;
      box = CellBox{layout.known_min - pad_cells, limits.num_x_cells, limits.num_y_cells};
    } else {
      pooled.emplace(MaxPoolGrid(*grid, factor, options_.unknown_probability, pad_cells));
      limits = pooled->limits();
      box = CellBox{Eigen::Array2i::Zero(), limits.num_x_cells, limits.num_y_cells};
    }
    const ProbabilityGrid& source = pooled.has_value() ? *pooled : *grid;
    const CellBox reads = cells_read(limits);
    const auto make_matcher = [&](const FastCorrelativeScanMatcherOptions2D& options) {
      return std::make_unique<FastCorrelativeScanMatcher2D>(
          limits,
          PrecomputationGridStack2D(source, box, options_.unknown_probability,
                                    options.branch_and_bound_depth, reads, &buffers_),
          options);
    };
    matcher_ = make_matcher(options_.fast_correlative_scan_matcher);
    if (options_.min_score_gain > 0.0) local_matcher_ = make_matcher(local);
    cached_submap_ = submap;
    cached_num_range_data_ = submap->num_range_data();
    cached_limits_ = limits;
    cached_reads_ = reads;
    ++num_precomputations_;
  }
  const double min_score = std::max(options_.fast_correlative_scan_matcher.min_score, min_fit);
  if (!matcher_->Match(predicted, cloud, min_score, score, pose)) return false;
  if (options_.min_score_gain <= 0.0) return true;
  // Along a featureless corridor many offsets score alike and the widest search may pick any
  // of them; the best pose near the prediction wins unless the wide answer is clearly better.
  double local_score = 0.0;
  common::Rigid2d local_pose;
  if (local_matcher_->Match(predicted, cloud, 0.0, &local_score, &local_pose) &&
      *score < local_score + options_.min_score_gain) {
    *score = local_score;
    *pose = local_pose;
  }
  return true;
}

}  // namespace mapping
}  // namespace fusemap
