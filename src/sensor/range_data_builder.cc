#include "fusemap/sensor/range_data_builder.h"

#include <algorithm>
#include <cmath>

namespace fusemap {
namespace sensor {

void RangeGateOptions::Check(common::OptionChecker* check) const {
  check->Require(min_range_m >= 0.f, "min_range_m", "must be >= 0");
  check->Require(max_range_m > min_range_m, "max_range_m", "must exceed min_range_m");
  check->Require(missing_data_ray_length_m > 0.f, "missing_data_ray_length_m", "must be > 0");
}

bool RangeGateOptions::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

RangeGateOptions ParseRangeGateOptions(common::ConfigReader& reader) {
  RangeGateOptions options;
  reader.Get("min_range_m", &options.min_range_m);
  reader.Get("max_range_m", &options.max_range_m);
  reader.Get("insert_misses", &options.insert_misses);
  reader.Get("missing_data_ray_length_m", &options.missing_data_ray_length_m);
  reader.CheckOptions(options);
  return options;
}

RangeData RangeDataFromScan(const LaserScan& scan, const RangeGateOptions& options) {
  RangeData range_data;
  const float min_m = std::max(scan.range_min_m, options.min_range_m);
  const float max_m = std::min(scan.range_max_m, options.max_range_m);
  range_data.returns.reserve(scan.ranges_m.size());
  for (size_t i = 0; i < scan.ranges_m.size(); ++i) {
    const float range_m = scan.ranges_m[i];
    // NaN compares false everywhere, so test it explicitly: it is treated as "no return".
    const bool no_return = std::isnan(range_m) || range_m >= max_m;
    if (!no_return && range_m < min_m) continue;
    const float angle_rad = scan.angle_min_rad + static_cast<float>(i) * scan.angle_increment_rad;
    const Eigen::Vector2f direction(std::cos(angle_rad), std::sin(angle_rad));
    if (!no_return) {
      range_data.returns.push_back(range_m * direction);
    } else if (options.insert_misses) {
      const float length_m = std::isfinite(range_m)
                                 ? std::min(options.missing_data_ray_length_m, range_m)
                                 : options.missing_data_ray_length_m;
      range_data.misses.push_back(length_m * direction);
    }
  }
  return range_data;
}

}  // namespace sensor
}  // namespace fusemap
