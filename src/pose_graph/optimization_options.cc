#include "fusemap/pose_graph/optimization_options.h"

#include <cmath>
#include <utility>

namespace fusemap {
namespace pose_graph {

void OptimizationOptions::Check(common::OptionChecker* check) const {
  check->Require(huber_scale >= 0.0 && std::isfinite(huber_scale), "huber_scale",
                 "must be finite and >= 0");
  check->Require(max_num_iterations >= 1, "max_num_iterations", "must be >= 1");
  check->Require(num_threads >= 1, "num_threads", "must be >= 1");
  check->Require(linear_solver == "sparse_normal_cholesky" || linear_solver == "dense_qr",
                 "linear_solver",
                 "must be sparse_normal_cholesky or dense_qr, not '" + linear_solver + "'");
  check->Require(function_tolerance > 0.0 && function_tolerance < 1.0, "function_tolerance",
                 "must be in (0, 1)");
}

bool OptimizationOptions::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

OptimizationOptions ParseOptimizationOptions(common::ConfigReader& reader,
                                             OptimizationOptions defaults) {
  OptimizationOptions options = std::move(defaults);
  reader.Get("huber_scale", &options.huber_scale);
  reader.Get("max_num_iterations", &options.max_num_iterations);
  reader.Get("num_threads", &options.num_threads);
  reader.Get("linear_solver", &options.linear_solver);
  reader.Get("function_tolerance", &options.function_tolerance);
  reader.CheckOptions(options);
  return options;
}

}  // namespace pose_graph
}  // namespace fusemap
