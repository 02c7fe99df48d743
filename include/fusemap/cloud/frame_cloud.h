#ifndef FUSEMAP_CLOUD_FRAME_CLOUD_H_
#define FUSEMAP_CLOUD_FRAME_CLOUD_H_

#include <cstdint>
#include <string>
#include <vector>

#include "fusemap/cloud/cloud_types.h"
#include "fusemap/common/config_reader.h"
#include "fusemap/sensor/rgbd_frame.h"

namespace fusemap {
namespace cloud {

// How one RGB-D frame becomes a filtered coloured cloud. Config keys (same names):
// min_range_m, max_range_m (depth-camera z gate), voxel_size_m (0 disables the voxel grid),
// outlier_mean_k (neighbours for statistical outlier removal; 0 disables it),
// outlier_stddev_mul, pixel_stride (use every n-th depth row and column).
struct FrameCloudOptions {
  double min_range_m = 0.2;
  double max_range_m = 5.5;
  double voxel_size_m = 0.03;
  int outlier_mean_k = 20;
  double outlier_stddev_mul = 2.0;
  int pixel_stride = 1;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

FrameCloudOptions ParseFrameCloudOptions(common::ConfigReader& reader);

// Where the points of one frame went, for health reporting and tests.
struct FrameCloudStats {
  int64_t input_pixels = 0;  // Depth pixels visited (after the stride).
  int64_t valid_depth = 0;   // Non-zero depth.
  int64_t out_of_range = 0;  // Valid depth outside [min_range_m, max_range_m].
  int64_t no_color = 0;      // In range but projecting outside the colour image.
  int64_t registered = 0;    // Coloured points entering the filters.
  int64_t after_voxel = 0;
  int64_t after_outlier = 0;
};

// Registers depth to colour (back-project with the depth intrinsics, move by T_color_depth,
// project with the colour intrinsics and take that pixel's colour), gates the range, and runs
// pcl::VoxelGrid and pcl::StatisticalOutlierRemoval. Points are in the colour camera's optical
// frame; T_base_camera = frame.T_base_color. A frame with no pixels gives an empty cloud.
// `stats` may be null.
CameraCloud BuildFrameCloud(const sensor::RgbdFrame& frame, const FrameCloudOptions& options,
                            FrameCloudStats* stats);

// The depth image registered to the colour camera by the same projection (metres, row-major,
// colour width x height; 0 where no depth in [min_range_m, max_range_m] lands, the nearest
// where several do): what an image-feature consumer (the visual loop checker) pairs with the
// colour image. Empty if the frame lacks images or intrinsics.
std::vector<float> RegisterDepthImage(const sensor::RgbdFrame& frame, double min_range_m,
                                      double max_range_m);

}  // namespace cloud
}  // namespace fusemap

#endif  // FUSEMAP_CLOUD_FRAME_CLOUD_H_
