#ifndef FUSEMAP_MAPPING_PROBABILITY_GRID_H_
#define FUSEMAP_MAPPING_PROBABILITY_GRID_H_

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "fusemap/mapping/map_limits.h"
#include "fusemap/mapping/probability_values.h"

namespace fusemap {
namespace mapping {

// Occupancy grid storing per-cell hit probability as 15-bit values (see probability_values.h).
// It grows (keeping cell contents at their world positions) when asked to cover a point outside,
// up to kMaxCells. Invariant: between updates no cell carries kUpdateMarker.
class ProbabilityGrid {
 public:
  // Most cells a grid grows to (512 MB; at 5 cm, 640 m x 640 m when grown from a submap's
  // start). Data that need more come from an absurd pose (a corrupt odometry message, a
  // diverged match), not from a building, and growing for them would overflow or never end.
  static constexpr int64_t kMaxCells = int64_t{1} << 28;

  explicit ProbabilityGrid(const MapLimits& limits);
  // A grid with the given cell values (checkpoint restore): one per cell, row-major as
  // MapLimits::FlatIndex, none carrying kUpdateMarker.
  ProbabilityGrid(const MapLimits& limits, std::vector<uint16_t> cells);

  const MapLimits& limits() const { return limits_; }
  // Raw cell values, row-major as MapLimits::FlatIndex (kUnknownValue for unknown cells).
  const std::vector<uint16_t>& cells() const { return cells_; }
  // Memory held by the cells.
  size_t bytes() const { return cells_.capacity() * sizeof(uint16_t); }

  // kMinProbability for unknown cells and for cells outside the grid.
  float GetProbability(const Eigen::Array2i& cell) const;
  // The same, but `unknown_probability` for cells never observed (and outside the grid):
  // what a scan matcher that counts unexplored space as no evidence reads.
  float GetProbabilityOr(const Eigen::Array2i& cell, float unknown_probability) const;
  bool IsKnown(const Eigen::Array2i& cell) const;
  uint16_t GetValue(const Eigen::Array2i& cell) const;
  // Sets a cell directly (tests, map loading). The cell must lie inside the grid.
  void SetProbability(const Eigen::Array2i& cell, float probability);

  // Applies an odds look-up table to a cell once per update; returns false if the cell was
  // already updated since the last FinishUpdate(). The cell must lie inside the grid.
  bool ApplyLookupTable(const Eigen::Array2i& cell, const std::vector<uint16_t>& table);
  // Clears the update markers set since the last call.
  void FinishUpdate();

  // Enlarges the grid (by doubling) until `point_m` falls inside, with a margin of a few cells.
  // Returns false, leaving the grid unchanged, if the point is not finite or covering it would
  // take more than kMaxCells.
  bool GrowLimits(const Eigen::Vector2f& point_m);
  // The same for the box [min_m, max_m], all or nothing.
  bool GrowLimits(const Eigen::Vector2f& min_m, const Eigen::Vector2f& max_m);
  // The limits GrowLimits(min_m, max_m) would give `limits`; empty where it would refuse.
  static std::optional<MapLimits> LimitsCovering(const MapLimits& limits, const Eigen::Vector2f& min_m,
                                                 const Eigen::Vector2f& max_m);

  // Bounding box (in cells) of the known cells; false if nothing is known. Kept up to date by
  // every write, so this is O(1): local SLAM crops its growing submap for a wide search.
  bool ComputeKnownBounds(Eigen::Array2i* min_cell, Eigen::Array2i* max_cell) const;

  // The smallest grid holding every known cell, at the same world positions. Growth by
  // doubling leaves mostly unknown space that loop-closure precomputation would pay for.
  ProbabilityGrid Cropped() const;

 private:
  // Widens the known bounds to `cell`, which has just become known.
  void ExtendKnownBounds(const Eigen::Array2i& cell) {
    if (!any_known_) {
      known_min_ = known_max_ = cell;
      any_known_ = true;
      return;
    }
    known_min_ = known_min_.min(cell);
    known_max_ = known_max_.max(cell);
  }

  MapLimits limits_;
  std::vector<uint16_t> cells_;
  std::vector<int> update_indices_;
  // Bounding box of the cells that are not kUnknownValue (valid while any_known_).
  bool any_known_ = false;
  Eigen::Array2i known_min_ = Eigen::Array2i::Zero();
  Eigen::Array2i known_max_ = Eigen::Array2i::Zero();
};

}  // namespace mapping
}  // namespace fusemap

#endif  // FUSEMAP_MAPPING_PROBABILITY_GRID_H_
