#include "fusemap/pose_graph/sparse_pose_adjustment_2d.h"

#include <algorithm>
#include <cassert>

#include "fusemap/pose_graph/se2_cost_function.h"
#include "fusemap/pose_graph/se2_graph.h"

namespace fusemap {
namespace pose_graph {

int SparsePoseAdjustment2D::AddSubmap(const common::Rigid2d& T_map_submap) {
  T_map_submaps_.push_back(T_map_submap);
  return static_cast<int>(T_map_submaps_.size()) - 1;
}

int SparsePoseAdjustment2D::AddNode(const common::Rigid2d& T_map_node) {
  T_map_nodes_.push_back(T_map_node);
  return static_cast<int>(T_map_nodes_.size()) - 1;
}

void SparsePoseAdjustment2D::AddConstraint(const Constraint2D& constraint) {
  assert(constraint.submap >= 0 && constraint.submap < static_cast<int>(T_map_submaps_.size()));
  assert(constraint.node >= 0 && constraint.node < static_cast<int>(T_map_nodes_.size()));
  assert(constraint.translation_weight > 0.0 && constraint.rotation_weight > 0.0);
  constraints_.push_back(constraint);
}

void SparsePoseAdjustment2D::AddNodeToNodeConstraint(const NodeToNodeConstraint2D& constraint) {
  assert(constraint.from >= 0 && constraint.from < static_cast<int>(T_map_nodes_.size()));
  assert(constraint.to >= 0 && constraint.to < static_cast<int>(T_map_nodes_.size()));
  assert(constraint.translation_weight > 0.0 && constraint.rotation_weight > 0.0);
  assert(constraint.weak_weight_fraction > 0.0 && constraint.weak_weight_fraction <= 1.0);
  node_to_node_constraints_.push_back(constraint);
}

void SparsePoseAdjustment2D::SetSubmapPose(int submap, const common::Rigid2d& T_map_submap) {
  assert(submap >= 0 && submap < static_cast<int>(T_map_submaps_.size()));
  T_map_submaps_[submap] = T_map_submap;
}

void SparsePoseAdjustment2D::SetNodePose(int node, const common::Rigid2d& T_map_node) {
  assert(node >= 0 && node < static_cast<int>(T_map_nodes_.size()));
  T_map_nodes_[node] = T_map_node;
}

OptimizationSummary SparsePoseAdjustment2D::Solve(const OptimizationOptions& options) {
  // Same code path as any SE(2) graph: submaps are vertices [0, S), nodes [S, S + N); a
  // node-in-submap constraint is an edge submap -> node with diagonal information (but for a
  // loop closure that measures nothing along one direction).
  const int num_submaps = static_cast<int>(T_map_submaps_.size());
  Se2Graph graph;
  graph.vertices = T_map_submaps_;
  graph.vertices.insert(graph.vertices.end(), T_map_nodes_.begin(), T_map_nodes_.end());
  graph.fixed.assign(graph.vertices.size(), false);
  if (num_submaps > 0) graph.fixed[0] = true;
  graph.edges.reserve(constraints_.size() + node_to_node_constraints_.size());
  for (const Constraint2D& c : constraints_) {
    graph.edges.push_back(
        {c.submap, num_submaps + c.node, c.T_submap_node,
         InformationWithoutMode(c.translation_weight, c.rotation_weight, c.unmeasured_direction,
                                c.unmeasured_turn_rad_per_m),
         c.tag == Constraint2D::kInterSubmap});
  }
  for (const NodeToNodeConstraint2D& c : node_to_node_constraints_) {
    graph.edges.push_back({num_submaps + c.from, num_submaps + c.to, c.T_from_to,
                           InformationFromWeights(c.translation_weight, c.rotation_weight,
                                                  c.weak_direction, c.weak_weight_fraction),
                           c.robust});
  }
  // Without submaps there is nothing to anchor the gauge the way Cartographer does.
  assert(num_submaps > 0 || graph.edges.empty());

  const OptimizationSummary summary = SolveSe2Graph(options, &graph);
  std::copy(graph.vertices.begin(), graph.vertices.begin() + num_submaps, T_map_submaps_.begin());
  std::copy(graph.vertices.begin() + num_submaps, graph.vertices.end(), T_map_nodes_.begin());
  ++solve_count_;
  return summary;
}

std::shared_ptr<const PoseGraphSnapshot> SparsePoseAdjustment2D::Snapshot() const {
  auto snapshot = std::make_shared<PoseGraphSnapshot>();
  snapshot->solve_count = solve_count_;
  snapshot->T_map_submaps = T_map_submaps_;
  snapshot->T_map_nodes = T_map_nodes_;
  return snapshot;
}

}  // namespace pose_graph
}  // namespace fusemap
