#include "fusemap/cloud/frame_cloud.h"

#include <pcl/filters/statistical_outlier_removal.h>
#include <pcl/filters/voxel_grid.h>

#include <cassert>
#include <cmath>

namespace fusemap {
namespace cloud {
namespace {

bool HasPixels(const sensor::PinholeIntrinsics& intrinsics) {
  return intrinsics.width > 0 && intrinsics.height > 0 && intrinsics.fx > 0.0 &&
         intrinsics.fy > 0.0;
}

// Back-projects the depth image (every `stride`-th row and column) into the colour camera and
// calls visit(p_color, color_col, color_row) for each point in range that lands on a colour
// pixel (nearest pixel; pixel centres at integer coordinates, as cx/cy assume). False if the
// frame lacks images or intrinsics.
template <typename Visit>
bool ForEachRegisteredPoint(const sensor::RgbdFrame& frame, int stride, double min_range_m,
                            double max_range_m, FrameCloudStats* stats, Visit&& visit) {
  const sensor::PinholeIntrinsics& depth = frame.depth_intrinsics;
  const sensor::PinholeIntrinsics& color = frame.color_intrinsics;
  const size_t depth_pixels = static_cast<size_t>(std::max(0, depth.width)) *
                              static_cast<size_t>(std::max(0, depth.height));
  const size_t color_pixels = static_cast<size_t>(std::max(0, color.width)) *
                              static_cast<size_t>(std::max(0, color.height));
  if (!HasPixels(depth) || !HasPixels(color) || frame.depth_mm.size() < depth_pixels ||
      frame.color_rgb.size() < 3 * color_pixels) {
    return false;
  }
  const Eigen::Matrix3d R_color_depth = frame.T_color_depth.rotation().toRotationMatrix();
  const Eigen::Vector3d t_color_depth = frame.T_color_depth.translation();
  for (int row = 0; row < depth.height; row += stride) {
    const uint16_t* depth_row = frame.depth_mm.data() + static_cast<size_t>(row) * depth.width;
    for (int col = 0; col < depth.width; col += stride) {
      ++stats->input_pixels;
      const uint16_t depth_mm = depth_row[col];
      if (depth_mm == 0) continue;
      ++stats->valid_depth;
      const double z_m = 1e-3 * depth_mm;
      if (z_m < min_range_m || z_m > max_range_m) {
        ++stats->out_of_range;
        continue;
      }
      const Eigen::Vector3d p_depth((col - depth.cx) * z_m / depth.fx,
                                    (row - depth.cy) * z_m / depth.fy, z_m);
      const Eigen::Vector3d p_color = R_color_depth * p_depth + t_color_depth;
      if (p_color.z() <= 0.0) {
        ++stats->no_color;
        continue;
      }
      const double u = color.fx * p_color.x() / p_color.z() + color.cx;
      const double v = color.fy * p_color.y() / p_color.z() + color.cy;
      const long color_col = std::lround(u);
      const long color_row = std::lround(v);
      if (color_col < 0 || color_row < 0 || color_col >= color.width || color_row >= color.height) {
        ++stats->no_color;
        continue;
      }
      visit(p_color, static_cast<int>(color_col), static_cast<int>(color_row));
    }
  }
  return true;
}

// Each registered point, coloured from the pixel it lands on.
ColorCloud::Ptr RegisterDepthToColor(const sensor::RgbdFrame& frame,
                                     const FrameCloudOptions& options, FrameCloudStats* stats) {
  auto cloud = pcl::make_shared<ColorCloud>();
  const sensor::PinholeIntrinsics& color = frame.color_intrinsics;
  const int stride = options.pixel_stride;
  cloud->reserve(frame.depth_mm.size() / static_cast<size_t>(stride * stride));
  ForEachRegisteredPoint(
      frame, stride, options.min_range_m, options.max_range_m, stats,
      [&](const Eigen::Vector3d& p_color, int color_col, int color_row) {
        const uint8_t* rgb = frame.color_rgb.data() +
                             3 * (static_cast<size_t>(color_row) * color.width + color_col);
        ColorPoint point(rgb[0], rgb[1], rgb[2]);
        point.x = static_cast<float>(p_color.x());
        point.y = static_cast<float>(p_color.y());
        point.z = static_cast<float>(p_color.z());
        cloud->push_back(point);
      });
  stats->registered = static_cast<int64_t>(cloud->size());
  return cloud;
}

}  // namespace

void FrameCloudOptions::Check(common::OptionChecker* check) const {
  check->Require(min_range_m >= 0.0, "min_range_m", "must be >= 0");
  check->Require(max_range_m > min_range_m, "max_range_m", "must be > min_range_m");
  check->Require(voxel_size_m >= 0.0, "voxel_size_m", "must be >= 0 (0 disables it)");
  check->Require(outlier_mean_k >= 0, "outlier_mean_k", "must be >= 0 (0 disables it)");
  check->Require(outlier_stddev_mul > 0.0, "outlier_stddev_mul", "must be > 0");
  check->Require(pixel_stride >= 1, "pixel_stride", "must be >= 1");
}

bool FrameCloudOptions::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

FrameCloudOptions ParseFrameCloudOptions(common::ConfigReader& reader) {
  FrameCloudOptions options;
  reader.Get("min_range_m", &options.min_range_m);
  reader.Get("max_range_m", &options.max_range_m);
  reader.Get("voxel_size_m", &options.voxel_size_m);
  reader.Get("outlier_mean_k", &options.outlier_mean_k);
  reader.Get("outlier_stddev_mul", &options.outlier_stddev_mul);
  reader.Get("pixel_stride", &options.pixel_stride);
  reader.CheckOptions(options);
  return options;
}

CameraCloud BuildFrameCloud(const sensor::RgbdFrame& frame, const FrameCloudOptions& options,
                            FrameCloudStats* stats) {
  assert(options.IsValid(nullptr));
  FrameCloudStats local_stats;
  if (stats == nullptr) stats = &local_stats;
  *stats = FrameCloudStats();

  CameraCloud result;
  result.stamp_s = frame.stamp_s;
  result.T_base_camera = frame.T_base_color;
  ColorCloud::Ptr cloud = RegisterDepthToColor(frame, options, stats);

  if (options.voxel_size_m > 0.0 && !cloud->empty()) {
    // VoxelGrid averages position and colour of the points in each cell.
    pcl::VoxelGrid<ColorPoint> voxel_grid;
    const float leaf_m = static_cast<float>(options.voxel_size_m);
    voxel_grid.setLeafSize(leaf_m, leaf_m, leaf_m);
    voxel_grid.setInputCloud(cloud);
    auto filtered = pcl::make_shared<ColorCloud>();
    voxel_grid.filter(*filtered);
    cloud = filtered;
  }
  stats->after_voxel = static_cast<int64_t>(cloud->size());

  if (options.outlier_mean_k > 0 && cloud->size() > static_cast<size_t>(options.outlier_mean_k)) {
    // Rusu et al. 2008: drop points whose mean distance to their k neighbours lies more than
    // stddev_mul standard deviations above the mean over the cloud.
    pcl::StatisticalOutlierRemoval<ColorPoint> outlier_removal;
    outlier_removal.setMeanK(options.outlier_mean_k);
    outlier_removal.setStddevMulThresh(options.outlier_stddev_mul);
    outlier_removal.setInputCloud(cloud);
    auto filtered = pcl::make_shared<ColorCloud>();
    outlier_removal.filter(*filtered);
    cloud = filtered;
  }
  stats->after_outlier = static_cast<int64_t>(cloud->size());
  result.points_camera = cloud;
  return result;
}

std::vector<float> RegisterDepthImage(const sensor::RgbdFrame& frame, double min_range_m,
                                      double max_range_m) {
  const sensor::PinholeIntrinsics& color = frame.color_intrinsics;
  std::vector<float> depth_m;
  FrameCloudStats stats;
  const size_t pixels = static_cast<size_t>(std::max(0, color.width)) *
                        static_cast<size_t>(std::max(0, color.height));
  depth_m.assign(pixels, 0.0f);
  const bool ok = ForEachRegisteredPoint(
      frame, 1, min_range_m, max_range_m, &stats,
      [&](const Eigen::Vector3d& p_color, int color_col, int color_row) {
        // Where several depth pixels land on one colour pixel, the nearest surface is seen.
        float& z = depth_m[static_cast<size_t>(color_row) * color.width + color_col];
        const float z_m = static_cast<float>(p_color.z());
        if (z == 0.0f || z_m < z) z = z_m;
      });
  if (!ok) depth_m.clear();
  return depth_m;
}

}  // namespace cloud
}  // namespace fusemap
