#include "fusemap/sensor/sensor_types.h"

namespace fusemap {
namespace sensor {

RangeData TransformRangeData(const RangeData& range_data, const common::Rigid2d& T_b_a) {
  RangeData out;
  out.origin = T_b_a * range_data.origin;
  out.returns.reserve(range_data.returns.size());
  for (const auto& p : range_data.returns) out.returns.push_back(T_b_a * p);
  out.misses.reserve(range_data.misses.size());
  for (const auto& p : range_data.misses) out.misses.push_back(T_b_a * p);
  return out;
}

}  // namespace sensor
}  // namespace fusemap
