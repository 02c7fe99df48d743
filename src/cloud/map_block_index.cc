#include "map_block_index.h"

#include <algorithm>
#include <cassert>

namespace fusemap {
namespace cloud {

MapBlockIndex::MapBlockIndex(double voxel_size_m, int block_voxels)
    : inv_voxel_size_(static_cast<float>(1.0 / voxel_size_m)), block_voxels_(block_voxels) {
  assert(voxel_size_m > 0.0);
  assert(block_voxels > 0);
}

void MapBlockIndex::Add(int region, uint32_t slot, const Eigen::Vector3f& center_map) {
  const VoxelKey block = BlockKey(VoxelIndex(center_map, inv_voxel_size_));
  if (last_refs_ == nullptr || block != last_block_ || region != last_region_) {
    last_refs_ = &blocks_[block];
    last_block_ = block;
    last_region_ = region;
    blocks_of_region_[region].insert(block);
  }
  last_refs_->push_back(RegionVoxelRef{region, slot});
}

void MapBlockIndex::RemoveRegion(int region) {
  last_refs_ = nullptr;
  auto it = blocks_of_region_.find(region);
  if (it == blocks_of_region_.end()) return;
  for (const VoxelKey block : it->second) {
    auto entries = blocks_.find(block);
    if (entries == blocks_.end()) continue;
    auto& refs = entries->second;
    refs.erase(std::remove_if(refs.begin(), refs.end(),
                              [region](const RegionVoxelRef& r) { return r.region == region; }),
               refs.end());
    if (refs.empty()) blocks_.erase(entries);
  }
  blocks_of_region_.erase(it);
}

const std::vector<RegionVoxelRef>* MapBlockIndex::Find(VoxelKey block_key) const {
  auto it = blocks_.find(block_key);
  return it == blocks_.end() ? nullptr : &it->second;
}

size_t MapBlockIndex::MemoryBytes() const {
  size_t bytes = sizeof(*this) + blocks_.bucket_count() * sizeof(void*);
  for (const auto& block : blocks_) {
    bytes += sizeof(block) + 16 + block.second.capacity() * sizeof(RegionVoxelRef);
  }
  for (const auto& region : blocks_of_region_) {
    bytes += sizeof(region) + 16 + region.second.size() * (sizeof(VoxelKey) + 16) +
             region.second.bucket_count() * sizeof(void*);
  }
  return bytes;
}

}  // namespace cloud
}  // namespace fusemap
