#ifndef FUSEMAP_POSE_GRAPH_MOVED_SUBMAPS_H_
#define FUSEMAP_POSE_GRAPH_MOVED_SUBMAPS_H_

#include <vector>

#include "fusemap/common/rigid_transform.h"

namespace fusemap {
namespace pose_graph {

// Below both a submap has not moved. The one definition of "moved" for everyone who attaches
// data to submaps: re-placing costs the cloud binder a rebuild of the submap's whole region, and
// 1e-6 m is below what a float32 map coordinate of a building-sized map can show.
constexpr double kSubmapMoveThresholdM = 1e-6;
constexpr double kSubmapMoveThresholdRad = 1e-7;

// Whether `after` is more than kSubmapMoveThresholdM or kSubmapMoveThresholdRad from `before`.
bool SubmapMoved(const common::Rigid2d& before, const common::Rigid2d& after);

// A submap a listener must place (is_new) or re-place at T_map_submap
// (PoseGraph2D::TakeSubmapPlacements).
struct SubmapPlacement {
  int submap = 0;
  common::Rigid2d T_map_submap;
  bool is_new = false;
};

// A submap whose map-frame pose changed in an optimisation: the event listeners (for example
// the RGB-D cloud binder) use to re-place what they attached to the submap.
struct SubmapMove {
  int submap = 0;
  common::Rigid2d T_map_submap_old;
  common::Rigid2d T_map_submap_new;
};

// Submaps (by index) that moved (SubmapMoved) between `before` and `after`, in index order.
// Submaps only in `after` are new, not moved, and are not listed.
std::vector<SubmapMove> MovedSubmaps(const std::vector<common::Rigid2d>& T_map_submaps_before,
                                     const std::vector<common::Rigid2d>& T_map_submaps_after);

}  // namespace pose_graph
}  // namespace fusemap

#endif  // FUSEMAP_POSE_GRAPH_MOVED_SUBMAPS_H_
