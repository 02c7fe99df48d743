#ifndef FUSEMAP_COMMON_MATH_H_
#define FUSEMAP_COMMON_MATH_H_

#include <algorithm>
#include <cmath>
#include <vector>

namespace fusemap {
namespace common {

constexpr double kPi = 3.14159265358979323846;

// Wraps an angle to [-pi, pi).
template <typename T>
T NormalizeAngle(T angle_rad) {
  using std::floor;
  const T two_pi = T(2.0 * kPi);
  return angle_rad - two_pi * floor((angle_rad + T(kPi)) / two_pi);
}

inline double DegToRad(double deg) { return deg * kPi / 180.0; }
inline double RadToDeg(double rad) { return rad * 180.0 / kPi; }

template <typename T>
T Clamp(T value, T lo, T hi) {
  return value < lo ? lo : (value > hi ? hi : value);
}

// Nearest-rank percentile (q in [0, 1]) of `values`: the element of rank round(q (n - 1)) in
// ascending order (for q = 0.5 the upper median); 0 when empty.
inline double Percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  const size_t i =
      std::min(values.size() - 1, static_cast<size_t>(q * (values.size() - 1) + 0.5));
  std::nth_element(values.begin(), values.begin() + i, values.end());
  return values[i];
}

}  // namespace common
}  // namespace fusemap

#endif  // FUSEMAP_COMMON_MATH_H_
