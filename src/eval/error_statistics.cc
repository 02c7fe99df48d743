#include "fusemap/eval/error_statistics.h"

#include <algorithm>
#include <cmath>

namespace fusemap {
namespace eval {

ErrorStatistics ComputeErrorStatistics(std::vector<double> errors) {
  ErrorStatistics stats;
  if (errors.empty()) return stats;
  const double n = static_cast<double>(errors.size());
  double sum = 0.0;
  double sum_sq = 0.0;
  for (const double e : errors) {
    sum += e;
    sum_sq += e * e;
  }
  stats.count = static_cast<int>(errors.size());
  stats.mean = sum / n;
  // Two-pass variance: the one-pass formula loses digits when std << mean.
  double sum_dev_sq = 0.0;
  for (const double e : errors) sum_dev_sq += (e - stats.mean) * (e - stats.mean);
  stats.std = std::sqrt(sum_dev_sq / n);
  stats.rmse = std::sqrt(sum_sq / n);
  std::sort(errors.begin(), errors.end());
  const size_t mid = errors.size() / 2;
  stats.median = errors.size() % 2 == 1 ? errors[mid] : 0.5 * (errors[mid - 1] + errors[mid]);
  stats.max = errors.back();
  return stats;
}

}  // namespace eval
}  // namespace fusemap
