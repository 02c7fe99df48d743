#include "fusemap/pose_graph/optimization_options.h"

#include <cmath>

namespace fusemap {
namespace pose_graph {

bool OptimizationOptions::IsValid(std::string* error) const {
  if (!(huber_scale >= 0.0) || !std::isfinite(huber_scale)) {
    *error = "huber_scale must be finite and >= 0";
    return false;
  }
  if (max_num_iterations < 1) {
    *error = "max_num_iterations must be >= 1";
    return false;
  }
  if (num_threads < 1) {
    *error = "num_threads must be >= 1";
    return false;
  }
  if (linear_solver != "sparse_normal_cholesky" && linear_solver != "dense_qr") {
    *error = "linear_solver must be sparse_normal_cholesky or dense_qr, not '" + linear_solver +
             "'";
    return false;
  }
  if (!(function_tolerance > 0.0) || !(function_tolerance < 1.0)) {
    *error = "function_tolerance must be in (0, 1)";
    return false;
  }
  return true;
}

OptimizationOptions ParseOptimizationOptions(common::ConfigReader& reader) {
  OptimizationOptions options;
  reader.Get("huber_scale", &options.huber_scale);
  reader.Get("max_num_iterations", &options.max_num_iterations);
  reader.Get("num_threads", &options.num_threads);
  reader.Get("linear_solver", &options.linear_solver);
  reader.Get("function_tolerance", &options.function_tolerance);
  std::string error;
  if (!options.IsValid(&error)) {
    // IsValid's messages start with the offending key.
    reader.AddError(error.substr(0, error.find(' ')), error.substr(error.find(' ') + 1));
  }
  return options;
}

}  // namespace pose_graph
}  // namespace fusemap
