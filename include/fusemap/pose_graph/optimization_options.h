#ifndef FUSEMAP_POSE_GRAPH_OPTIMIZATION_OPTIONS_H_
#define FUSEMAP_POSE_GRAPH_OPTIMIZATION_OPTIONS_H_

#include <string>

#include "fusemap/common/config_reader.h"

namespace fusemap {
namespace pose_graph {

// Options for one nonlinear least-squares solve of an SE(2) pose graph (sparse pose adjustment,
// Konolige et al. 2010; Hess et al. 2016 Sec. IV).
struct OptimizationOptions {
  // Scale of the Huber loss on robust (loop-closure) edges, in units of the whitened residual;
  // 0 disables the loss. Cartographer's pose graph uses a Huber loss on loop closures only.
  double huber_scale = 1e-1;
  int max_num_iterations = 50;
  int num_threads = 1;
  // "sparse_normal_cholesky" (SuiteSparse, else Eigen sparse, else CXSparse, whichever this
  // Ceres has) or "dense_qr" (small problems only).
  std::string linear_solver = "sparse_normal_cholesky";
  // Relative decrease of the cost below which the solve counts as converged.
  double function_tolerance = 1e-6;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

// Keys: huber_scale, max_num_iterations, num_threads, linear_solver, function_tolerance. Keys
// absent keep their value in `defaults` (the pose graph's own differ from a plain graph's).
OptimizationOptions ParseOptimizationOptions(common::ConfigReader& reader,
                                             OptimizationOptions defaults = {});

// Costs are Ceres costs, 0.5 * sum of squared (robustified) whitened residuals; g2o's chi2 of
// the same graph without a robust loss is 2 * cost.
struct OptimizationSummary {
  double initial_cost = 0.0;
  double final_cost = 0.0;
  int iterations = 0;
  double wall_s = 0.0;
  // True if Ceres stopped on a convergence criterion, false on the iteration limit or failure.
  bool converged = false;
};

}  // namespace pose_graph
}  // namespace fusemap

#endif  // FUSEMAP_POSE_GRAPH_OPTIMIZATION_OPTIONS_H_
