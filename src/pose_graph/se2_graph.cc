#include "fusemap/pose_graph/se2_graph.h"

#include <ceres/ceres.h>

#include <array>
#include <cassert>
#include <cstdlib>
#include <deque>
#include <limits>
#include <string>

#include "fusemap/pose_graph/se2_cost_function.h"

namespace fusemap {
namespace pose_graph {
namespace {

void SetLinearSolver(const OptimizationOptions& options, ceres::Solver::Options* solver) {
  if (options.linear_solver == "dense_qr") {
    solver->linear_solver_type = ceres::DENSE_QR;
    return;
  }
  // Debian's Ceres 2.1 has SuiteSparse, Eigen sparse and CXSparse; other builds may lack some.
  solver->linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  for (const ceres::SparseLinearAlgebraLibraryType library :
       {ceres::SUITE_SPARSE, ceres::EIGEN_SPARSE, ceres::CX_SPARSE}) {
    if (ceres::IsSparseLinearAlgebraLibraryTypeAvailable(library)) {
      solver->sparse_linear_algebra_library_type = library;
      return;
    }
  }
  solver->linear_solver_type = ceres::DENSE_QR;
}

}  // namespace

OptimizationSummary SolveSe2Graph(const OptimizationOptions& options, Se2Graph* graph) {
  std::string error;
  assert(options.IsValid(&error));
  const int num_vertices = static_cast<int>(graph->vertices.size());
  assert(graph->fixed.empty() || static_cast<int>(graph->fixed.size()) == num_vertices);

  std::vector<std::array<double, 3>> poses(num_vertices);
  for (int i = 0; i < num_vertices; ++i) {
    const common::Rigid2d& pose = graph->vertices[i];
    poses[i] = {pose.x(), pose.y(), pose.angle_rad()};
  }

  ceres::Problem problem;
  for (const Se2Edge& edge : graph->edges) {
    assert(edge.from >= 0 && edge.from < num_vertices && edge.to >= 0 && edge.to < num_vertices);
    Eigen::Matrix3d sqrt_information;
    const bool positive_definite = SqrtInformation(edge.information, &sqrt_information);
    assert(positive_definite);
    (void)positive_definite;
    ceres::LossFunction* loss = (edge.robust && options.huber_scale > 0.0)
                                    ? new ceres::HuberLoss(options.huber_scale)
                                    : nullptr;
    problem.AddResidualBlock(CreateSe2EdgeCostFunction(edge.T_from_to, sqrt_information), loss,
                             poses[edge.from].data(), poses[edge.to].data());
  }

  OptimizationSummary result;
  if (problem.NumResidualBlocks() == 0) {
    result.converged = true;
    return result;
  }

  bool any_fixed = false;
  for (int i = 0; i < static_cast<int>(graph->fixed.size()); ++i) {
    if (graph->fixed[i] && problem.HasParameterBlock(poses[i].data())) {
      problem.SetParameterBlockConstant(poses[i].data());
      any_fixed = true;
    }
  }
  // The cost is invariant to a global rigid motion; hold one pose to remove that gauge freedom.
  if (!any_fixed && problem.HasParameterBlock(poses[0].data())) {
    problem.SetParameterBlockConstant(poses[0].data());
  }

  ceres::Solver::Options solver_options;
  SetLinearSolver(options, &solver_options);
  solver_options.max_num_iterations = options.max_num_iterations;
  solver_options.num_threads = options.num_threads;
  solver_options.function_tolerance = options.function_tolerance;
  solver_options.minimizer_progress_to_stdout = false;
  solver_options.logging_type = ceres::SILENT;

  ceres::Solver::Summary summary;
  ceres::Solve(solver_options, &problem, &summary);

  for (int i = 0; i < num_vertices; ++i) {
    graph->vertices[i] = common::Rigid2d(poses[i][0], poses[i][1], poses[i][2]);
  }
  result.initial_cost = summary.initial_cost;
  result.final_cost = summary.final_cost;
  result.iterations = summary.num_successful_steps + summary.num_unsuccessful_steps;
  result.wall_s = summary.total_time_in_seconds;
  result.converged = summary.termination_type == ceres::CONVERGENCE;
  return result;
}

OptimizationSummary SolveSe2GraphRobustThenPlain(const OptimizationOptions& options,
                                                 Se2Graph* graph) {
  OptimizationSummary robust;
  const double initial_cost = Se2GraphCost(*graph);
  if (options.huber_scale > 0.0) robust = SolveSe2Graph(options, graph);
  OptimizationOptions plain_options = options;
  plain_options.huber_scale = 0.0;
  OptimizationSummary summary = SolveSe2Graph(plain_options, graph);
  summary.initial_cost = initial_cost;
  summary.iterations += robust.iterations;
  summary.wall_s += robust.wall_s;
  return summary;
}

double Se2GraphCost(const Se2Graph& graph) {
  double cost = 0.0;
  for (const Se2Edge& edge : graph.edges) {
    const Eigen::Vector3d e = Se2EdgeError(graph.vertices[edge.from], graph.vertices[edge.to],
                                           edge.T_from_to);
    cost += 0.5 * e.dot(edge.information * e);
  }
  return cost;
}

int InitializeFromEdges(Se2Graph* graph) {
  const int num_vertices = static_cast<int>(graph->vertices.size());
  if (num_vertices == 0) return 0;
  std::vector<std::vector<int>> incident(num_vertices);
  for (int e = 0; e < static_cast<int>(graph->edges.size()); ++e) {
    incident[graph->edges[e].from].push_back(e);
    incident[graph->edges[e].to].push_back(e);
  }
  // 0-1 BFS: odometry edges cost 0, others 1, so each vertex is reached through as few
  // loop closures as possible; poses are composed when a vertex is settled.
  constexpr int kUnreached = std::numeric_limits<int>::max();
  std::vector<int> distance(num_vertices, kUnreached);
  std::vector<int> parent_edge(num_vertices, -1);
  std::vector<bool> settled(num_vertices, false);
  std::deque<int> queue = {0};
  distance[0] = 0;
  int num_reached = 0;
  while (!queue.empty()) {
    const int u = queue.front();
    queue.pop_front();
    if (settled[u]) continue;
    settled[u] = true;
    ++num_reached;
    if (parent_edge[u] >= 0) {
      const Se2Edge& edge = graph->edges[parent_edge[u]];
      graph->vertices[u] = edge.to == u ? graph->vertices[edge.from] * edge.T_from_to
                                        : graph->vertices[edge.to] * edge.T_from_to.inverse();
    }
    for (const int e : incident[u]) {
      const Se2Edge& edge = graph->edges[e];
      const int v = edge.from == u ? edge.to : edge.from;
      const int weight = std::abs(edge.to - edge.from) == 1 ? 0 : 1;
      if (settled[v] || distance[u] + weight >= distance[v]) continue;
      distance[v] = distance[u] + weight;
      parent_edge[v] = e;
      if (weight == 0) {
        queue.push_front(v);
      } else {
        queue.push_back(v);
      }
    }
  }
  return num_reached;
}

}  // namespace pose_graph
}  // namespace fusemap
