#include "free_space_carver.h"

#include <octomap/OcTree.h>

#include <algorithm>
#include <cassert>

namespace fusemap {
namespace cloud {
namespace {

// octomap keys are floor(coordinate / resolution) + 2^15 (OcTreeBaseImpl::coordToKey), so the
// same integer grid as VoxelIndex once the offset is removed.
constexpr int kOctomapKeyOffset = 32768;

Eigen::Vector3i ToVoxelIndex(const octomap::OcTreeKey& key) {
  return Eigen::Vector3i(static_cast<int>(key[0]) - kOctomapKeyOffset,
                         static_cast<int>(key[1]) - kOctomapKeyOffset,
                         static_cast<int>(key[2]) - kOctomapKeyOffset);
}

bool NearHit(const Eigen::Vector3i& index, const std::unordered_set<VoxelKey>& hits) {
  for (int dx = -1; dx <= 1; ++dx) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dz = -1; dz <= 1; ++dz) {
        if (hits.count(PackVoxelKey(index + Eigen::Vector3i(dx, dy, dz))) != 0) return true;
      }
    }
  }
  return false;
}

}  // namespace

FreeSpaceCarver::FreeSpaceCarver(const FreeSpaceCarverOptions& options)
    : options_(options),
      inv_voxel_size_(static_cast<float>(1.0 / options.voxel_size_m)),
      key_tree_(new octomap::OcTree(options.voxel_size_m)) {
  assert(options.voxel_size_m > 0.0 && options.ray_stride >= 1 && options.margin_voxels >= 0);
}

FreeSpaceCarver::~FreeSpaceCarver() = default;

std::unordered_set<VoxelKey> FreeSpaceCarver::CarvedVoxels(
    const Eigen::Vector3f& origin_map, const std::vector<Eigen::Vector3f>& points_map,
    const MapBlockIndex& index, int frame_index) const {
  std::unordered_set<VoxelKey> carved;
  if (points_map.empty()) return carved;
  std::unordered_set<VoxelKey> near_hit;  // candidates already found too close to a hit
  std::unordered_set<VoxelKey> hits;
  hits.reserve(points_map.size());
  for (const Eigen::Vector3f& p : points_map) hits.insert(KeyOf(p, inv_voxel_size_));

  const float voxel_size = static_cast<float>(options_.voxel_size_m);
  const float margin_fixed_m = static_cast<float>(options_.margin_voxels) * voxel_size;
  const float margin_fraction = static_cast<float>(options_.margin_range_fraction);
  const float max_length = static_cast<float>(options_.max_ray_length_m);
  const octomap::point3d origin(origin_map.x(), origin_map.y(), origin_map.z());
  octomap::KeyRay ray;
  const size_t first = static_cast<size_t>(frame_index) % options_.ray_stride;
  for (size_t i = first; i < points_map.size(); i += options_.ray_stride) {
    const Eigen::Vector3f delta = points_map[i] - origin_map;
    const float range = delta.norm();
    const float margin_m = std::max(margin_fixed_m, margin_fraction * range);
    if (range <= margin_m + voxel_size) continue;
    const Eigen::Vector3f direction = delta / range;
    // Beyond max_length the end is not a surface, only the end of trusted free space.
    const float length = std::min(range, max_length);
    const float carve_until = range <= max_length ? range - margin_m : max_length;
    const Eigen::Vector3f end = origin_map + length * direction;
    if (!key_tree_->computeRayKeys(origin, octomap::point3d(end.x(), end.y(), end.z()), ray)) {
      continue;  // outside octomap's key range (about +-980 m at 3 cm): nothing to carve there
    }
    VoxelKey last_block = 0;
    bool last_block_occupied = false;
    bool have_last_block = false;
    for (const octomap::OcTreeKey& key : ray) {
      const Eigen::Vector3i voxel = ToVoxelIndex(key);
      const Eigen::Vector3f center =
          (voxel.cast<float>() + Eigen::Vector3f::Constant(0.5f)) * voxel_size;
      if ((center - origin_map).dot(direction) >= carve_until) break;
      const VoxelKey block = index.BlockKey(voxel);
      if (!have_last_block || block != last_block) {
        last_block = block;
        last_block_occupied = index.Find(block) != nullptr;
        have_last_block = true;
      }
      if (!last_block_occupied) continue;
      const VoxelKey voxel_key = PackVoxelKey(voxel);
      if (carved.count(voxel_key) != 0 || near_hit.count(voxel_key) != 0) continue;
      if (NearHit(voxel, hits)) {
        near_hit.insert(voxel_key);
      } else {
        carved.insert(voxel_key);
      }
    }
  }
  return carved;
}

}  // namespace cloud
}  // namespace fusemap
