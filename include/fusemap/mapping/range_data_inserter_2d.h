#ifndef FUSEMAP_MAPPING_RANGE_DATA_INSERTER_2D_H_
#define FUSEMAP_MAPPING_RANGE_DATA_INSERTER_2D_H_

#include <cstdint>
#include <string>
#include <vector>

#include "fusemap/common/config_reader.h"
#include "fusemap/mapping/probability_grid.h"
#include "fusemap/sensor/sensor_types.h"

namespace fusemap {
namespace mapping {

struct ProbabilityGridRangeDataInserterOptions {
  float hit_probability = 0.55f;
  float miss_probability = 0.49f;
  bool insert_free_space = true;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

ProbabilityGridRangeDataInserterOptions ParseProbabilityGridRangeDataInserterOptions(
    common::ConfigReader& reader);

// The bounding box of the origin, returns and misses; false if any coordinate is not finite.
bool RangeDataBounds(const sensor::RangeData& range_data, Eigen::Vector2f* min_m, Eigen::Vector2f* max_m);

// Writes one scan into a probability grid with the odds update of Hess et al. 2016, eq. 2.
// Every touched cell is updated at most once per Insert(): hits first, then the free cells
// along each ray, so a cell hit by this scan is never also cleared by it.
class RangeDataInserter2D {
 public:
  explicit RangeDataInserter2D(const ProbabilityGridRangeDataInserterOptions& options);

  // `range_data` must be in the grid's frame. Grows the grid to cover the origin and every
  // point (false, grid unchanged, if it cannot: see ProbabilityGrid::GrowLimits), then applies the hit table to return cells and (if insert_free_space) the miss
  // table to cells crossed by rays to returns (excluding the return cell) and to misses
  // (including the end cell).
  bool Insert(const sensor::RangeData& range_data, ProbabilityGrid* grid) const;

 private:
  ProbabilityGridRangeDataInserterOptions options_;
  std::vector<uint16_t> hit_table_;
  std::vector<uint16_t> miss_table_;
};

}  // namespace mapping
}  // namespace fusemap

#endif  // FUSEMAP_MAPPING_RANGE_DATA_INSERTER_2D_H_
