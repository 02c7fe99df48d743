#ifndef FUSEMAP_CLOUD_FREE_SPACE_CARVER_H_
#define FUSEMAP_CLOUD_FREE_SPACE_CARVER_H_

#include <Eigen/Core>
#include <memory>
#include <unordered_set>
#include <vector>

#include "map_block_index.h"
#include "voxel_key.h"

namespace octomap {
class OcTree;
}  // namespace octomap

namespace fusemap {
namespace cloud {

struct FreeSpaceCarverOptions {
  double voxel_size_m = 0.03;
  int ray_stride = 4;                   // every ray_stride-th point casts a ray
  int margin_voxels = 3;                // a ray carves only up to this many voxels before its end,
  double margin_range_fraction = 0.05;  // or this fraction of its range, whichever is more
  double max_ray_length_m = 5.5;
};

// Finds the map voxels one depth frame saw through: voxels a ray from the camera origin
// traverses (Amanatides-Woo traversal via octomap's computeRayKeys) strictly before its endpoint
// minus a margin. Two guards keep static surfaces safe at grazing angles, where a ray ending on
// a wall runs inside that wall's voxels for a while before its end: the margin, and skipping
// any voxel within one voxel (26-neighbourhood) of a point this same frame observed, since the
// frame itself says a surface is there. The margin grows with range because far returns on a
// grazed floor are sparser than a voxel (a 0.35 deg pixel at 5 m and 11 deg grazing spans 16 cm
// of floor), so the neighbourhood guard has gaps there and a ray would run inside the floor's
// voxels for r / sin(grazing) before its end (r = voxel half-diagonal). Only voxels in blocks of
// `index` are reported: empty space has nothing to carve, so the result stays small.
class FreeSpaceCarver {
 public:
  explicit FreeSpaceCarver(const FreeSpaceCarverOptions& options);
  ~FreeSpaceCarver();
  FreeSpaceCarver(const FreeSpaceCarver&) = delete;
  FreeSpaceCarver& operator=(const FreeSpaceCarver&) = delete;

  // `frame_index` rotates which points cast rays, so that a camera standing still still
  // covers every pixel over ray_stride frames instead of leaving the same gaps each time.
  std::unordered_set<VoxelKey> CarvedVoxels(const Eigen::Vector3f& origin_map,
                                            const std::vector<Eigen::Vector3f>& points_map,
                                            const MapBlockIndex& index, int frame_index) const;

 private:
  FreeSpaceCarverOptions options_;
  float inv_voxel_size_;
  // Used only for its key arithmetic (computeRayKeys); it holds no nodes.
  std::unique_ptr<octomap::OcTree> key_tree_;
};

}  // namespace cloud
}  // namespace fusemap

#endif  // FUSEMAP_CLOUD_FREE_SPACE_CARVER_H_
