#ifndef FUSEMAP_CLOUD_VOXEL_KEY_H_
#define FUSEMAP_CLOUD_VOXEL_KEY_H_

#include <Eigen/Core>
#include <cmath>
#include <cstdint>

namespace fusemap {
namespace cloud {

// Integer voxel coordinates packed into one hashable word: 21 bits per axis, offset so that
// indices in [-2^20, 2^20) fit (about +-31 km at 3 cm voxels, far beyond any indoor map).
// Voxel k covers [k * size, (k + 1) * size) on each axis.
using VoxelKey = uint64_t;

constexpr int kVoxelKeyBits = 21;
constexpr int64_t kVoxelKeyOffset = int64_t{1} << (kVoxelKeyBits - 1);
constexpr uint64_t kVoxelKeyMask = (uint64_t{1} << kVoxelKeyBits) - 1;

inline VoxelKey PackVoxelKey(const Eigen::Vector3i& index) {
  return (static_cast<uint64_t>(index.x() + kVoxelKeyOffset) & kVoxelKeyMask) |
         ((static_cast<uint64_t>(index.y() + kVoxelKeyOffset) & kVoxelKeyMask) << kVoxelKeyBits) |
         ((static_cast<uint64_t>(index.z() + kVoxelKeyOffset) & kVoxelKeyMask)
          << (2 * kVoxelKeyBits));
}

inline Eigen::Vector3i UnpackVoxelKey(VoxelKey key) {
  return Eigen::Vector3i(
      static_cast<int>(int64_t(key & kVoxelKeyMask) - kVoxelKeyOffset),
      static_cast<int>(int64_t((key >> kVoxelKeyBits) & kVoxelKeyMask) - kVoxelKeyOffset),
      static_cast<int>(int64_t((key >> (2 * kVoxelKeyBits)) & kVoxelKeyMask) - kVoxelKeyOffset));
}

inline Eigen::Vector3i VoxelIndex(const Eigen::Vector3f& p, float inv_voxel_size) {
  return Eigen::Vector3i(static_cast<int>(std::floor(p.x() * inv_voxel_size)),
                         static_cast<int>(std::floor(p.y() * inv_voxel_size)),
                         static_cast<int>(std::floor(p.z() * inv_voxel_size)));
}

inline VoxelKey KeyOf(const Eigen::Vector3f& p, float inv_voxel_size) {
  return PackVoxelKey(VoxelIndex(p, inv_voxel_size));
}

inline Eigen::Vector3f VoxelCenter(VoxelKey key, float voxel_size) {
  return (UnpackVoxelKey(key).cast<float>() + Eigen::Vector3f::Constant(0.5f)) * voxel_size;
}

// Key of the coarser block (block_voxels^3 voxels) that contains voxel `index`.
inline VoxelKey BlockKeyOf(const Eigen::Vector3i& index, int block_voxels) {
  auto floor_div = [block_voxels](int v) {
    return v >= 0 ? v / block_voxels : -((-v + block_voxels - 1) / block_voxels);
  };
  return PackVoxelKey(
      Eigen::Vector3i(floor_div(index.x()), floor_div(index.y()), floor_div(index.z())));
}

}  // namespace cloud
}  // namespace fusemap

#endif  // FUSEMAP_CLOUD_VOXEL_KEY_H_
