#ifndef FUSEMAP_CLOUD_MAP_BLOCK_INDEX_H_
#define FUSEMAP_CLOUD_MAP_BLOCK_INDEX_H_

#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "voxel_key.h"

namespace fusemap {
namespace cloud {

// A voxel of some region: which region, which slot in it.
struct RegionVoxelRef {
  int32_t region = 0;
  uint32_t slot = 0;
};

// Map-frame spatial hash over all regions' voxels, bucketed in coarse blocks (block_voxels^3
// map voxels) so that the index stays small (8 bytes per voxel) and a ray can skip empty space
// a block at a time. Entries are placed by the voxel's map-frame centre; dead slots may linger
// until their region is re-indexed, so users check liveness. Each region remembers its blocks,
// so re-indexing a moved region costs its own voxels plus those sharing its blocks.
class MapBlockIndex {
 public:
  MapBlockIndex(double voxel_size_m, int block_voxels);

  void Add(int region, uint32_t slot, const Eigen::Vector3f& center_map);
  // Drops every entry of `region` (before it is re-added under a new pose).
  void RemoveRegion(int region);

  // Entries of a block (see BlockKey), or nullptr if the block holds none.
  const std::vector<RegionVoxelRef>* Find(VoxelKey block_key) const;
  VoxelKey BlockKey(const Eigen::Vector3i& voxel_index) const {
    return BlockKeyOf(voxel_index, block_voxels_);
  }
  float inv_voxel_size() const { return inv_voxel_size_; }
  int block_voxels() const { return block_voxels_; }
  // Every non-empty block by key, for visiting the map voxels near a camera.
  const std::unordered_map<VoxelKey, std::vector<RegionVoxelRef>>& blocks() const {
    return blocks_;
  }
  size_t MemoryBytes() const;

 private:
  float inv_voxel_size_;
  int block_voxels_;
  std::unordered_map<VoxelKey, std::vector<RegionVoxelRef>> blocks_;
  std::unordered_map<int, std::unordered_set<VoxelKey>> blocks_of_region_;
  // Consecutive Adds mostly land in the same block: skip the two hash look-ups then.
  // (Element references of unordered_map survive rehashing; RemoveRegion resets this.)
  int last_region_ = 0;
  VoxelKey last_block_ = 0;
  std::vector<RegionVoxelRef>* last_refs_ = nullptr;
};

}  // namespace cloud
}  // namespace fusemap

#endif  // FUSEMAP_CLOUD_MAP_BLOCK_INDEX_H_
