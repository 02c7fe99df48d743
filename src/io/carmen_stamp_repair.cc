#include "carmen_stamp_repair.h"

#include <algorithm>
#include <cassert>
#include <cctype>
#include <cmath>
#include <cstdlib>

namespace fusemap {
namespace io {

double PrintedStampResolution(const std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || !std::isfinite(value) || value == 0.0) return 0.0;
  // Digits of the mantissa: significant ones (after leading zeros) and those after the point.
  int significant = 0, decimals = 0;
  bool after_point = false, leading = true;
  size_t i = 0;
  for (; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '.') {
      after_point = true;
    } else if (std::isdigit(static_cast<unsigned char>(c))) {
      if (c != '0') leading = false;
      if (!leading) ++significant;
      if (after_point) ++decimals;
    } else if (c == 'e' || c == 'E') {
      break;
    } else if (c != '+' && c != '-') {
      return 0.0;
    }
  }
  const int exponent = i < text.size() ? std::atoi(text.c_str() + i + 1) : 0;
  const double text_resolution_s = std::pow(10.0, exponent - decimals);
  if (significant > 6) return text_resolution_s;
  const double six_digit_resolution_s =
      std::pow(10.0, std::floor(std::log10(std::abs(value))) - 5.0);
  return std::min(text_resolution_s, six_digit_resolution_s);
}

std::vector<double> SpreadOverRounding(double printed_s, double resolution_s,
                                       const std::vector<bool>& starts_instant) {
  assert(resolution_s >= 0.0);
  const size_t n = starts_instant.size();
  std::vector<int> instant(n, 0);
  for (size_t i = 1; i < n; ++i) instant[i] = instant[i - 1] + (starts_instant[i] ? 1 : 0);
  const int k = n == 0 ? 0 : instant.back() + 1;
  std::vector<double> stamps(n, printed_s);
  if (k < 2) return stamps;
  for (size_t i = 0; i < n; ++i) {
    stamps[i] = printed_s - 0.5 * resolution_s + (instant[i] + 0.5) * resolution_s / k;
  }
  return stamps;
}

}  // namespace io
}  // namespace fusemap
