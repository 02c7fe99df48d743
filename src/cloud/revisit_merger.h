#ifndef FUSEMAP_CLOUD_REVISIT_MERGER_H_
#define FUSEMAP_CLOUD_REVISIT_MERGER_H_

#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include "fusemap/cloud/cloud_types.h"
#include "fusemap/common/rigid_transform.h"
#include "map_block_index.h"

namespace fusemap {
namespace cloud {

class RegionStack;

struct RevisitMergeOptions {
  // A voxel of a region more than carve_window submap ids from the frame's own matches only
  // if it has at least min_hits_beyond_window hits (see CloudBinderOptions).
  int carve_window = 2;
  int min_hits_beyond_window = 1;
};

// A point of a frame that falls into a live voxel of another region.
struct RevisitMatch {
  uint32_t point = 0;  // index into the points searched
  RegionVoxelRef voxel;
  Eigen::Vector3f p_submap = Eigen::Vector3f::Zero();  // the point in that region's submap frame
};

// Revisit search: for each map-frame point of a frame bound to region `own_region`, the live
// voxel of another region whose cell (in that region's own submap grid, at the index's voxel
// size) contains the point; if several regions have one, the voxel with the most hits. Matches
// come in ascending point order. Candidates are the regions indexed in the point's map block and
// its 26 neighbours (a submap voxel's centre, by which the index places it, lies within
// sqrt(3)/2 voxels of any point in it); only the entries of blocks within one voxel of a point
// are read, so the cost is those entries plus the points times the few regions near each.
// Testing the point against the region's own grid (rather than comparing map-frame voxel
// indices of the point and of voxel centres) matches every point of a surface the region
// already holds, whatever the submaps' relative rotation.
std::vector<RevisitMatch> FindRevisitedVoxels(
    const std::vector<Eigen::Vector3f>& points_map, int own_region,
    const RevisitMergeOptions& options, const MapBlockIndex& index,
    const std::map<int, std::unique_ptr<RegionStack>>& regions);

// Merges each finite point (camera at T_map_camera) of a frame bound to `own_region` that
// FindRevisitedVoxels matches into that voxel (RegionStack::AddHit, in its submap frame) and
// returns the other finite points, camera frame, for the own region's Insert. Adds the number
// merged to *merged.
ColorCloud::Ptr MergeRevisits(const ColorCloud& points_camera, const common::Rigid3d& T_map_camera,
                              int own_region, int frame_index, const RevisitMergeOptions& options,
                              const MapBlockIndex& index,
                              std::map<int, std::unique_ptr<RegionStack>>* regions,
                              int64_t* merged);

}  // namespace cloud
}  // namespace fusemap

#endif  // FUSEMAP_CLOUD_REVISIT_MERGER_H_
