#ifndef FUSEMAP_POSE_GRAPH_SE2_GRAPH_H_
#define FUSEMAP_POSE_GRAPH_SE2_GRAPH_H_

#include <Eigen/Core>
#include <vector>

#include "fusemap/common/rigid_transform.h"
#include "fusemap/pose_graph/optimization_options.h"

namespace fusemap {
namespace pose_graph {

// A relative-pose measurement between two vertices (by index): T_from_to with its 3x3
// information matrix over (x, y, theta) in the measurement frame (g2o's EDGE_SE2).
struct Se2Edge {
  int from = 0;
  int to = 0;
  common::Rigid2d T_from_to;
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
  // Robust edges get the Huber loss (loop closures, which may be wrong).
  bool robust = false;
};

// A plain SE(2) pose graph: vertex poses T_map_vertex by index, optional external ids (g2o
// vertex ids, same order), which vertices are held constant, and edges between indices.
// Invariants: ids and fixed are empty or the size of vertices; edges reference valid indices.
struct Se2Graph {
  std::vector<common::Rigid2d> vertices;
  std::vector<int> ids;
  std::vector<bool> fixed;
  std::vector<Se2Edge> edges;
};

// Solves the graph in place (sparse pose adjustment, Konolige et al. 2010) with
// CreateSe2EdgeCostFunction for every edge. If no vertex is fixed, vertex 0 is held constant
// to fix the gauge. Every information matrix must be positive definite (asserted).
OptimizationSummary SolveSe2Graph(const OptimizationOptions& options, Se2Graph* graph);

// For poor initial values (e.g. MIT.g2o, where plain least squares stalls in a bad basin): if
// options.huber_scale > 0, first solves with the Huber loss on robust edges, then again without
// any loss from that result. The summary's costs are plain least-squares costs (Se2GraphCost)
// of the initial and final poses; iterations and wall_s add up both passes; converged is the
// second pass's. With huber_scale == 0 this is one plain pass.
OptimizationSummary SolveSe2GraphRobustThenPlain(const OptimizationOptions& options,
                                                 Se2Graph* graph);

// 0.5 * sum of e^T information e over all edges, without robust loss: the Ceres cost of the
// plain least-squares problem (g2o's chi2 is twice this).
double Se2GraphCost(const Se2Graph& graph);

// Overwrites the poses of all vertices reachable from vertex 0 by composing edge measurements
// along a spanning tree that prefers odometry edges (indices differing by one), the usual
// initial guess for files that carry no vertex estimates. Returns the number of vertices reached.
int InitializeFromEdges(Se2Graph* graph);

}  // namespace pose_graph
}  // namespace fusemap

#endif  // FUSEMAP_POSE_GRAPH_SE2_GRAPH_H_
