#ifndef FUSEMAP_SENSOR_RANGE_DATA_BUILDER_H_
#define FUSEMAP_SENSOR_RANGE_DATA_BUILDER_H_

#include <string>

#include "fusemap/common/config_reader.h"
#include "fusemap/sensor/sensor_types.h"

namespace fusemap {
namespace sensor {

// Which measured ranges count as returns. The gate narrows the sensor's own
// [range_min_m, range_max_m): near readings are often the robot body, far ones too noisy for
// matching. Beams without a usable return still carve free space up to
// missing_data_ray_length_m (Cartographer's missing_data_ray_length).
struct RangeGateOptions {
  float min_range_m = 0.1f;
  float max_range_m = 30.f;
  // Turns no-return beams into misses; off for sensors whose "no return" may mean "blocked".
  bool insert_misses = true;
  float missing_data_ray_length_m = 5.f;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

RangeGateOptions ParseRangeGateOptions(common::ConfigReader& reader);

// Converts a scan into RangeData in the sensor frame (origin at zero). A beam whose range lies
// in [max(scan.range_min_m, min_range_m), min(scan.range_max_m, max_range_m)) is a return.
// A beam with no return (>= the sensor maximum, NaN, inf) or beyond the gate maximum becomes a
// miss at missing_data_ray_length_m along the beam, shortened to the measured range when that
// is finite so free space is never carved past a real obstacle. Beams below the minimum are
// dropped.
RangeData RangeDataFromScan(const LaserScan& scan, const RangeGateOptions& options);

}  // namespace sensor
}  // namespace fusemap

#endif  // FUSEMAP_SENSOR_RANGE_DATA_BUILDER_H_
