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
#include "fusemap/sensor/rgbd_frame.h"

namespace fusemap {
namespace cloud {

class DepthCarver;
class FreeSpaceCarver;
class MapBlockIndex;
class RegionStack;
struct RegionVoxelRef;

struct CloudBinderOptions {
  double voxel_size_m = 0.03;  // merge grid of every region, in submap coordinates
  bool remove_dynamic = true;
  // How frames see through map points: false = projectively, against each frame's depth image
  // (CarveWithDepth, cheap enough for every frame); true = by casting rays from the points of
  // each bound cloud in AddCloud (FreeSpaceCarver; for clouds without a depth image).
  bool ray_carving = false;
  int carve_pixel_stride = 4;  // projective: depth image cell size, pixels
  int carve_window_cells = 1;  // projective: nearest depth within +-this many cells counts
  double dynamic_no_return_carve_m = 3.0;  // projective: see DepthCarver::SeesThrough
  // Projective: a frame bound to submap s carves only regions s - w .. s + w. Submaps close in
  // time share local SLAM's odometry chain and agree to millimetres; a region from an earlier
  // lap is placed by loop closure, and a 1 deg / 5 cm disagreement with the current frame's
  // pose moves a wall seen at a 15 deg grazing angle 20 cm in depth - in front of what the
  // frame measures, so it would be carved. People are carved within a few seconds anyway.
  int carve_submap_window = 2;
  // A voxel is dynamic once carves >= dynamic_carves_per_hit * hits (both counted in frames).
  double dynamic_carves_per_hit = 1.0;
  int dynamic_ray_stride = 4;     // every n-th point of a frame casts a free-space ray
  int dynamic_margin_voxels = 3;  // rays carve only up to this many voxels before their end,
  double dynamic_margin_range_fraction = 0.05;  // or this fraction of their range if more
  double dynamic_max_ray_length_m = 5.5;
  int index_block_voxels = 8;  // map-frame spatial hash bucket edge, in voxels
  // Regions that most recently received clouds keep their merge hash; older ones free it
  // (clouds bind to the active submaps, so the hash of a finished one is dead weight).
  int regions_with_merge_index = 4;
  // Revisits: a point of a frame that falls into a live voxel of another region (in that
  // region's submap grid) is merged into that voxel instead of starting a voxel in the frame's
  // own region, so a loop driven again and again does not store its walls once per lap. Uses
  // the map-frame index, which is then kept even without remove_dynamic.
  bool merge_revisits = false;
  // ... but into a region more than carve_submap_window submaps away only if the voxel was seen
  // in at least this many frames: frames cannot carve such a region, so hits they add to a
  // voxel (a person's) could never be outweighed by the current lap's free-space evidence.
  int merge_min_hits_beyond_window = 2;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

// Keys: voxel_size_m, remove_dynamic, ray_carving, carve_pixel_stride, carve_window_cells,
// carve_submap_window, dynamic_no_return_carve_m, dynamic_carves_per_hit, dynamic_ray_stride, dynamic_margin_voxels,
// dynamic_margin_range_fraction, dynamic_max_ray_length_m, index_block_voxels,
// regions_with_merge_index, merge_revisits, merge_min_hits_beyond_window.
CloudBinderOptions ParseCloudBinderOptions(common::ConfigReader& reader);

struct CloudBinderStats {
  int64_t frames = 0;        // clouds bound
  int64_t carve_frames = 0;  // depth images carved with
  int64_t points_in = 0;     // finite points handed to AddCloud
  size_t points_stored = 0;  // live voxels = points in GlobalCloud()
  size_t regions = 0;
  int64_t points_removed_dynamic = 0;
  int64_t points_merged_into_other_regions = 0;  // merge_revisits: points not stored anew
  int64_t rebuilt_points_total = 0;  // map-frame points recomputed by re-posing, ever
  size_t last_update_regions = 0;    // of the last OnSubmapsMoved / SetSubmapPose
  size_t last_update_points = 0;
  double last_update_ms = 0.0;
  double last_frame_ms = 0.0;  // last AddCloud, carving included
  double last_carve_ms = 0.0;        // ray carving inside the last AddCloud
  double last_merge_ms = 0.0;        // revisit search and merge inside the last AddCloud
  double last_depth_carve_ms = 0.0;  // last CarveWithDepth
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

  // Counts a depth image (depth camera at T_submap_depth in submap `submap_id`'s frame) as
  // free-space evidence against every live map point it sees through (projective carving; a
  // no-op with ray_carving or without remove_dynamic). Call it for every frame, bound or not,
  // before AddCloud of the same frame.
  void CarveWithDepth(int submap_id, const common::Rigid3d& T_submap_depth,
                      const sensor::PinholeIntrinsics& intrinsics,
                      const std::vector<uint16_t>& depth_mm);

  // Binds a filtered frame cloud (colour camera frame) to `submap_id`.
  void AddCloud(int submap_id, const common::Rigid3d& T_submap_camera, const CameraCloud& cloud);

  // All live points in the map frame (one per occupied region voxel).
  // With `hits`, also how many frames saw each point's voxel (same order).
  ColorCloud::Ptr GlobalCloud(std::vector<uint16_t>* hits = nullptr) const;
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
  bool UsesIndex() const { return options_.remove_dynamic || options_.merge_revisits; }

  size_t Repose(int submap_id, const common::Rigid3d& T_map_submap);
  void IndexSlots(int submap_id, const RegionStack& region, const std::vector<uint32_t>& slots);
  void CarveFreeSpace(const common::Rigid3d& T_map_camera, const ColorCloud& points_camera,
                      int frame_index);
  // Counts a carve of each listed voxel and removes the ones judged dynamic.
  void ApplyCarves(const std::vector<RegionVoxelRef>& carved, int frame_index);

  CloudBinderOptions options_;
  std::map<int, std::unique_ptr<RegionStack>> regions_;
  std::map<int, common::Rigid3d> T_map_submaps_;
  std::vector<int> recent_regions_;  // most recent last; at most regions_with_merge_index
  std::unique_ptr<MapBlockIndex> index_;
  std::unique_ptr<FreeSpaceCarver> carver_;
  std::unique_ptr<DepthCarver> depth_carver_;
  int next_frame_index_ = 0;  // shared by bound clouds and carving images
  ColorCloud::Ptr removed_points_;
  CloudBinderStats stats_;
};

}  // namespace cloud
}  // namespace fusemap

#endif  // FUSEMAP_CLOUD_CLOUD_BINDER_H_
