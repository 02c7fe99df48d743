#ifndef FUSEMAP_POSE_GRAPH_MOVED_SUBMAPS_H_
#define FUSEMAP_POSE_GRAPH_MOVED_SUBMAPS_H_

#include <vector>

#include "fusemap/common/rigid_transform.h"

namespace fusemap {
namespace pose_graph {

// A submap whose map-frame pose changed in an optimisation: the event listeners (for example
// the RGB-D cloud binder) use to re-place what they attached to the submap.
struct SubmapMove {
  int submap = 0;
  common::Rigid2d T_map_submap_old;
  common::Rigid2d T_map_submap_new;
};

// Submaps (by index) whose translation moved by more than translation_threshold_m or whose
// angle moved by more than rotation_threshold_rad between `before` and `after`, in index order.
// Submaps only in `after` are new, not moved, and are not listed.
std::vector<SubmapMove> MovedSubmaps(const std::vector<common::Rigid2d>& T_map_submaps_before,
                                     const std::vector<common::Rigid2d>& T_map_submaps_after,
                                     double translation_threshold_m = 1e-4,
                                     double rotation_threshold_rad = 1e-5);

}  // namespace pose_graph
}  // namespace fusemap

#endif  // FUSEMAP_POSE_GRAPH_MOVED_SUBMAPS_H_
