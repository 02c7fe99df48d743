#ifndef FUSEMAP_POSE_GRAPH_SPARSE_POSE_ADJUSTMENT_2D_H_
#define FUSEMAP_POSE_GRAPH_SPARSE_POSE_ADJUSTMENT_2D_H_

#include <cstdint>
#include <memory>
#include <vector>

#include "fusemap/common/rigid_transform.h"
#include "fusemap/pose_graph/optimization_options.h"
#include "fusemap/pose_graph/pose_graph_snapshot.h"
#include "fusemap/pose_graph/pose_graph_types.h"

namespace fusemap {
namespace pose_graph {

// The optimisation problem of Cartographer's global SLAM (Hess et al. 2016 Sec. IV, Eq. (SPA)):
// submap and node poses in the map frame, node-in-submap constraints and node-to-node
// odometry/local-SLAM constraints, solved by sparse pose adjustment (Konolige et al. 2010).
// The first submap is held constant; the Huber loss applies to loop closures (kInterSubmap)
// only. Not thread-safe and starts no threads: one owner calls it, others get snapshots.
class SparsePoseAdjustment2D {
 public:
  SparsePoseAdjustment2D() = default;
  SparsePoseAdjustment2D(const SparsePoseAdjustment2D&) = delete;
  SparsePoseAdjustment2D& operator=(const SparsePoseAdjustment2D&) = delete;

  // Return the new submap/node index.
  int AddSubmap(const common::Rigid2d& T_map_submap);
  int AddNode(const common::Rigid2d& T_map_node);
  // Indices must exist (asserted).
  void AddConstraint(const Constraint2D& constraint);
  void AddNodeToNodeConstraint(const NodeToNodeConstraint2D& constraint);
  void SetSubmapPose(int submap, const common::Rigid2d& T_map_submap);
  void SetNodePose(int node, const common::Rigid2d& T_map_node);

  // Optimises all poses in place; `options` must be valid (asserted).
  OptimizationSummary Solve(const OptimizationOptions& options);

  const std::vector<common::Rigid2d>& T_map_submaps() const { return T_map_submaps_; }
  const std::vector<common::Rigid2d>& T_map_nodes() const { return T_map_nodes_; }
  const std::vector<Constraint2D>& constraints() const { return constraints_; }
  const std::vector<NodeToNodeConstraint2D>& node_to_node_constraints() const {
    return node_to_node_constraints_;
  }

  // A copy of the current poses for other threads.
  std::shared_ptr<const PoseGraphSnapshot> Snapshot() const;

 private:
  std::vector<common::Rigid2d> T_map_submaps_;
  std::vector<common::Rigid2d> T_map_nodes_;
  std::vector<Constraint2D> constraints_;
  std::vector<NodeToNodeConstraint2D> node_to_node_constraints_;
  std::uint64_t solve_count_ = 0;
};

}  // namespace pose_graph
}  // namespace fusemap

#endif  // FUSEMAP_POSE_GRAPH_SPARSE_POSE_ADJUSTMENT_2D_H_
