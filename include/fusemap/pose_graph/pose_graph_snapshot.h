#ifndef FUSEMAP_POSE_GRAPH_POSE_GRAPH_SNAPSHOT_H_
#define FUSEMAP_POSE_GRAPH_POSE_GRAPH_SNAPSHOT_H_

#include <cstdint>
#include <vector>

#include "fusemap/common/rigid_transform.h"

namespace fusemap {
namespace pose_graph {

// Optimised poses at one moment, handed to other threads as
// std::shared_ptr<const PoseGraphSnapshot>; never changed after it is made.
struct PoseGraphSnapshot {
  // Number of completed solves when the snapshot was taken; larger is newer.
  std::uint64_t solve_count = 0;
  std::vector<common::Rigid2d> T_map_submaps;
  // The nodes the graph holds: their indices and poses.
  std::vector<int> node_ids;
  std::vector<common::Rigid2d> T_map_nodes;
};

}  // namespace pose_graph
}  // namespace fusemap

#endif  // FUSEMAP_POSE_GRAPH_POSE_GRAPH_SNAPSHOT_H_
