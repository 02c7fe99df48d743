#ifndef FUSEMAP_EVAL_ERROR_STATISTICS_H_
#define FUSEMAP_EVAL_ERROR_STATISTICS_H_

#include <vector>

namespace fusemap {
namespace eval {

// Summary of a set of non-negative error magnitudes. std is the population standard deviation
// (divide by N), as in the published Kümmerle et al. (2009) and TUM benchmark figures.
struct ErrorStatistics {
  int count = 0;
  double mean = 0.0;
  double std = 0.0;
  double rmse = 0.0;
  double median = 0.0;
  double max = 0.0;
};

// All fields zero when `errors` is empty.
ErrorStatistics ComputeErrorStatistics(std::vector<double> errors);

}  // namespace eval
}  // namespace fusemap

#endif  // FUSEMAP_EVAL_ERROR_STATISTICS_H_
