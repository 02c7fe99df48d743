#ifndef FUSEMAP_CLOUD_REGION_STACK_H_
#define FUSEMAP_CLOUD_REGION_STACK_H_

#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "fusemap/cloud/cloud_types.h"
#include "fusemap/common/rigid_transform.h"
#include "voxel_key.h"

namespace fusemap {
namespace cloud {

// One merged voxel of a region, in submap coordinates. hits and carves count distinct frames
// (saturating), so a voxel's evidence does not depend on how many points a frame put into it.
struct RegionVoxel {
  VoxelKey key = 0;  // in the submap's voxel grid
  Eigen::Vector3f mean_submap = Eigen::Vector3f::Zero();
  Eigen::Vector3f mean_rgb = Eigen::Vector3f::Zero();
  uint32_t num_points = 0;  // points merged (0 marks a removed slot)
  uint16_t hits = 0;        // frames that saw a point in this voxel
  uint16_t carves = 0;      // later frames whose rays passed clearly through it
  int32_t last_hit_frame = -1;
  int32_t last_carve_frame = -1;

  bool alive() const { return num_points > 0; }
};

// The regional stack of one submap: every frame cloud bound to the submap, merged on a voxel
// grid in submap coordinates (one point per occupied voxel: its mean position and colour), plus
// a cached map-frame copy of those points under the submap's current pose. Slots are stable:
// a removed voxel leaves a dead slot (NaN in the cache), so references into the region stay
// valid. Invariant: map_cloud()[i] == T_map_submap * voxels()[i].mean_submap for live slots.
class RegionStack {
 public:
  // carves_per_hit: see Carve().
  RegionStack(double voxel_size_m, const common::Rigid3d& T_map_submap,
              double carves_per_hit = 1.0);

  // Merges points given in the camera frame into the grid. Slots of voxels this call created
  // are appended to *new_slots (for the caller's map-frame index).
  void Insert(const ColorCloud& points_camera, const common::Rigid3d& T_submap_camera,
              int frame_index, std::vector<uint32_t>* new_slots);
  // Merges one point (submap frame, inside the voxel's cell) into the live voxel in `slot`
  // exactly as Insert merges into an existing voxel: running means, num_points, one hit per
  // frame; refreshes the slot's map-frame point. For points of frames bound to other submaps.
  void AddHit(uint32_t slot, const Eigen::Vector3f& p_submap, const Eigen::Vector3f& rgb,
              int frame_index);

  // Frees the key-to-slot hash (about 40 bytes per voxel) of a region that no longer receives
  // clouds; the next Insert rebuilds it from the voxels. Everything else keeps working.
  void ReleaseKeyIndex();
  bool has_key_index() const { return has_key_index_; }

  // Re-poses the region: rebuilds the cached map-frame cloud. Returns the points rebuilt.
  size_t SetPose(const common::Rigid3d& T_map_submap);

  // Frame `frame_index` saw through the voxel in `slot`; returns true if the voxel is now
  // judged dynamic (see the rule in the .cc), in which case the caller should Remove() it.
  bool Carve(uint32_t slot, int frame_index);
  // Kills the voxel in `slot`; returns its map-frame point.
  ColorPoint Remove(uint32_t slot);

  // Map-frame centre of the submap voxel in `slot`: a stable stand-in for the voxel when it is
  // tested against map-frame rays (the mean moves as points merge, the centre does not).
  Eigen::Vector3f CenterInMap(uint32_t slot) const;

  const common::Rigid3d& T_map_submap() const { return T_map_submap_; }
  const std::vector<RegionVoxel>& voxels() const { return voxels_; }
  const ColorCloud& map_cloud() const { return *map_cloud_; }
  size_t num_alive() const { return num_alive_; }
  size_t MemoryBytes() const;

 private:
  ColorPoint ToMapPoint(const RegionVoxel& voxel) const;

  float voxel_size_m_;
  float inv_voxel_size_;
  float carves_per_hit_;
  common::Rigid3d T_map_submap_;
  Eigen::Matrix3f R_map_submap_;
  Eigen::Vector3f t_map_submap_;
  std::unordered_map<VoxelKey, uint32_t> slot_of_key_;
  bool has_key_index_ = true;
  std::vector<RegionVoxel> voxels_;
  ColorCloud::Ptr map_cloud_;
  size_t num_alive_ = 0;
};

}  // namespace cloud
}  // namespace fusemap

#endif  // FUSEMAP_CLOUD_REGION_STACK_H_
