#ifndef FUSEMAP_CLOUD_DEPTH_CARVER_H_
#define FUSEMAP_CLOUD_DEPTH_CARVER_H_

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "fusemap/sensor/rgbd_frame.h"

namespace fusemap {
namespace cloud {

struct DepthCarverOptions {
  int pixel_stride = 4;   // the depth image is reduced to cells of stride x stride pixels
  int window_cells = 1;   // a point is tested against the nearest depth within +-this many cells
  double min_range_m = 0.2;
  double max_range_m = 5.5;             // points farther away are never carved
  double margin_m = 0.09;               // a point must lie this far in front of the surface,
  double margin_range_fraction = 0.05;  // or this fraction of its depth if more
  double no_return_carve_m = 3.0;       // see SeesThrough
};

// Projective free-space test against one depth image (the visibility check of e.g. Kim & Kim,
// "Remove, then Revert", IROS 2020, in its simplest form): a map point is seen through when it
// projects into the image in front of the measured depth. It costs one projection per map point
// in the view instead of a ray traversal per pixel, so every frame can carve, not only the
// frames bound into the map. Static surfaces are protected by taking the NEAREST depth in a
// window around the projected pixel (a point on an edge or a grazed floor then compares against
// its own surface, not the background beside it) and by a range-dependent margin that covers
// voxel size and depth noise.
class DepthCarver {
 public:
  explicit DepthCarver(const DepthCarverOptions& options);

  // Prepares the window-minimum cell image of one depth frame (depth in mm, 0 = no return).
  void SetImage(const sensor::PinholeIntrinsics& intrinsics, const std::vector<uint16_t>& depth_mm);

  // True if the point (depth camera frame, z forward) lies clearly in front of what the image
  // measured there. Where no pixel of the window returned anything, the point is seen through
  // only up to no_return_carve_m: a missing return usually means free space beyond the sensor
  // range, but a surface the sensor cannot see (glass, black cloth) also returns nothing, and
  // such surfaces are never in the map either, so a bounded no-return carve removes only what
  // stood in front of them; beyond a few metres a dropout is too likely to be a far surface the
  // camera merely missed to trust it.
  bool SeesThrough(const Eigen::Vector3f& p_depth) const;

  // The frustum side planes of the current image (inward normals), for culling blocks.
  const std::vector<Eigen::Vector3f>& side_normals() const { return side_normals_; }
  const DepthCarverOptions& options() const { return options_; }

 private:
  DepthCarverOptions options_;
  sensor::PinholeIntrinsics intrinsics_;
  int cells_x_ = 0;
  int cells_y_ = 0;
  std::vector<float> cell_min_m_;    // nearest return per cell (+inf if none)
  std::vector<float> window_min_m_;  // nearest return over the window around each cell
  std::vector<Eigen::Vector3f> side_normals_;
};

}  // namespace cloud
}  // namespace fusemap

#endif  // FUSEMAP_CLOUD_DEPTH_CARVER_H_
