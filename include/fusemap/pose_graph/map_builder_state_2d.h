#ifndef FUSEMAP_POSE_GRAPH_MAP_BUILDER_STATE_2D_H_
#define FUSEMAP_POSE_GRAPH_MAP_BUILDER_STATE_2D_H_

#include <vector>

#include "fusemap/mapping/local_trajectory_builder_2d.h"
#include "fusemap/mapping/submap_2d.h"
#include "fusemap/pose_graph/pose_graph_2d.h"

namespace fusemap {
namespace pose_graph {

// The full state of a MapBuilder2D as plain values, so that mapping can stop (checkpoint)
// and continue later exactly where it stopped. Options are not part of it: the restoring
// program supplies them. Invariants (checked by io::ReadCheckpoint for data from disk):
// pose_graph.submaps, pose_graph.T_map_submaps and submaps have one entry per submap; all
// node and submap indices are in range; each active submap index appears in `submaps`.
struct MapBuilderState2D {
  std::vector<mapping::SubmapState2D> submaps;  // by pose-graph submap index
  PoseGraphState2D pose_graph;
  mapping::LocalTrajectoryBuilderState2D local_slam;
  std::vector<int> active_submaps;  // local SLAM's active submaps, oldest first
};

}  // namespace pose_graph
}  // namespace fusemap

#endif  // FUSEMAP_POSE_GRAPH_MAP_BUILDER_STATE_2D_H_
