#ifndef FUSEMAP_CLOUD_CLOUD_BINDER_H_
#define FUSEMAP_CLOUD_CLOUD_BINDER_H_

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "fusemap/cloud/cloud_types.h"
#include "fusemap/common/config_reader.h"
#include "fusemap/common/rigid_transform.h"

namespace fusemap {
namespace cloud {

class FreeSpaceCarver;
class MapBlockIndex;
class RegionStack;

struct CloudBinderOptions {
  double voxel_size_m = 0.03;  // merge grid of every region, in submap coordinates
  bool remove_dynamic = true;
  int dynamic_ray_stride = 4;     // every n-th point of a frame casts a free-space ray
  int dynamic_margin_voxels = 3;  // rays carve only up to this many voxels before their end,
  double dynamic_margin_range_fraction = 0.05;  // or this fraction of their range if more
  double dynamic_max_ray_length_m = 5.5;
  int index_block_voxels = 8;  // map-frame spatial hash bucket edge, in voxels
  // Regions that most recently received clouds keep their merge hash; older ones free it
  // (clouds bind to the active submaps, so the hash of a finished one is dead weight).
  int regions_with_merge_index = 4;

  bool IsValid(std::string* error) const;
};

// Keys: voxel_size_m, remove_dynamic, dynamic_ray_stride, dynamic_margin_voxels,
// dynamic_margin_range_fraction, dynamic_max_ray_length_m, index_block_voxels,
// regions_with_merge_index.
CloudBinderOptions ParseCloudBinderOptions(common::ConfigReader& reader);

struct CloudBinderStats {
  int64_t frames = 0;
  int64_t points_in = 0;     // finite points handed to AddCloud
  size_t points_stored = 0;  // live voxels = points in GlobalCloud()
  size_t regions = 0;
  int64_t points_removed_dynamic = 0;
  int64_t rebuilt_points_total = 0;  // map-frame points recomputed by re-posing, ever
  size_t last_update_regions = 0;    // of the last OnSubmapsMoved / SetSubmapPose
  size_t last_update_points = 0;
  double last_update_ms = 0.0;
  double last_frame_ms = 0.0;  // last AddCloud, carving included
  double last_carve_ms = 0.0;
};

// Binds RGB-D frame clouds to laser submaps: each cloud is stored in the frame of the submap
// active when it was taken, merged into that submap's region (see RegionStack), and the global
// map is the union of regions under their current T_map_submap. When global SLAM moves
// submaps, only their regions are re-posed, so an update costs the moved regions' points.
// With remove_dynamic, each frame's rays first carve earlier map points they see through
// (FreeSpaceCarver); voxels whose free-space evidence outweighs their hits are moved to
// removed_points(). Not thread-safe: the daemon owns one per thread.
class CloudBinder {
 public:
  explicit CloudBinder(const CloudBinderOptions& options);
  ~CloudBinder();
  CloudBinder(const CloudBinder&) = delete;
  CloudBinder& operator=(const CloudBinder&) = delete;

  // Places a submap (new or moved). A region first seen in AddCloud sits at the identity until
  // its pose is set, so set the pose of a new submap before binding clouds to it.
  void SetSubmapPose(int submap_id, const common::Rigid3d& T_map_submap);
  // Re-poses exactly the listed regions (submaps without clouds are remembered for later).
  void OnSubmapsMoved(const std::vector<std::pair<int, common::Rigid3d>>& moved);

  // Binds a filtered frame cloud (colour camera frame) to `submap_id`.
  void AddCloud(int submap_id, const common::Rigid3d& T_submap_camera, const CameraCloud& cloud);

  // All live points in the map frame (one per occupied region voxel).
  ColorCloud::Ptr GlobalCloud() const;
  // One region's live points in the map frame; empty if the submap has no clouds.
  ColorCloud::Ptr RegionCloud(int submap_id) const;
  // Points removed as dynamic, in the map frame at the time of removal.
  const ColorCloud& removed_points() const { return *removed_points_; }

  const CloudBinderStats& stats() const { return stats_; }
  const CloudBinderOptions& options() const { return options_; }
  std::vector<int> SubmapIds() const;
  // Approximate heap use of regions, index and removed points.
  size_t MemoryBytes() const;

 private:
  RegionStack& GetOrCreateRegion(int submap_id);
  size_t Repose(int submap_id, const common::Rigid3d& T_map_submap);
  void IndexSlots(int submap_id, const RegionStack& region, const std::vector<uint32_t>& slots);
  void CarveFreeSpace(const common::Rigid3d& T_map_camera, const ColorCloud& points_camera,
                      int frame_index);

  CloudBinderOptions options_;
  std::map<int, std::unique_ptr<RegionStack>> regions_;
  std::map<int, common::Rigid3d> T_map_submaps_;
  std::vector<int> recent_regions_;  // most recent last; at most regions_with_merge_index
  std::unique_ptr<MapBlockIndex> index_;
  std::unique_ptr<FreeSpaceCarver> carver_;
  ColorCloud::Ptr removed_points_;
  CloudBinderStats stats_;
};

}  // namespace cloud
}  // namespace fusemap

#endif  // FUSEMAP_CLOUD_CLOUD_BINDER_H_
