#include "fusemap/cloud/frame_cloud.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fusemap {
namespace cloud {
namespace {

sensor::PinholeIntrinsics Intrinsics(int width, int height, double f) {
  sensor::PinholeIntrinsics k;
  k.width = width;
  k.height = height;
  k.fx = f;
  k.fy = f;
  k.cx = 0.5 * (width - 1);
  k.cy = 0.5 * (height - 1);
  return k;
}

// A 160x120 depth camera facing a flat wall at depth_mm, and a 320x240 colour camera whose left
// half (u < 160, i.e. x < 0 in its optical frame) is red and right half blue.
sensor::RgbdFrame WallFrame(uint16_t depth_mm) {
  sensor::RgbdFrame frame;
  frame.stamp_s = 12.5;
  frame.depth_intrinsics = Intrinsics(160, 120, 120.0);
  frame.color_intrinsics = Intrinsics(320, 240, 240.0);
  frame.depth_mm.assign(160 * 120, depth_mm);
  frame.color_rgb.resize(320 * 240 * 3);
  for (int row = 0; row < 240; ++row) {
    for (int col = 0; col < 320; ++col) {
      uint8_t* rgb = &frame.color_rgb[3 * (row * 320 + col)];
      rgb[0] = col < 160 ? 255 : 0;
      rgb[2] = col < 160 ? 0 : 255;
    }
  }
  frame.T_base_color =
      common::Rigid3d(Eigen::Vector3d(0.2, 0.0, 0.5), Eigen::Quaterniond(0.5, -0.5, 0.5, -0.5));
  return frame;
}

FrameCloudOptions NoFilters() {
  FrameCloudOptions options;
  options.voxel_size_m = 0.0;
  options.outlier_mean_k = 0;
  return options;
}

TEST(FrameCloudTest, FlatWallGivesPointsAtItsDepth) {
  const sensor::RgbdFrame frame = WallFrame(2000);
  FrameCloudStats stats;
  const CameraCloud cloud = BuildFrameCloud(frame, FrameCloudOptions(), &stats);
  ASSERT_NE(cloud.points_camera, nullptr);
  ASSERT_GT(cloud.points_camera->size(), 1000u);
  EXPECT_EQ(stats.input_pixels, 160 * 120);
  EXPECT_EQ(stats.valid_depth, 160 * 120);
  EXPECT_EQ(stats.registered, 160 * 120);
  EXPECT_EQ(stats.after_outlier, static_cast<int64_t>(cloud.points_camera->size()));
  for (const ColorPoint& p : *cloud.points_camera) EXPECT_NEAR(p.z, 2.0, 0.03);
  EXPECT_DOUBLE_EQ(cloud.stamp_s, 12.5);
  EXPECT_TRUE(cloud.T_base_camera.translation().isApprox(frame.T_base_color.translation()));
  EXPECT_TRUE(cloud.T_base_camera.rotation().isApprox(frame.T_base_color.rotation()));
}

TEST(FrameCloudTest, RegistrationUsesExtrinsicAndBothIntrinsics) {
  sensor::RgbdFrame frame = WallFrame(2000);
  // The colour camera sits 0.1 m to the left of the depth camera: p_color = p_depth + 0.1 x.
  frame.T_color_depth = common::Rigid3d(Eigen::Vector3d(0.1, 0.0, 0.0), Eigen::Quaterniond::Identity());
  FrameCloudStats stats;
  const CameraCloud cloud = BuildFrameCloud(frame, NoFilters(), &stats);
  // Depth columns 154..159 land right of the colour image (u >= 319.5): 6 columns x 120 rows.
  EXPECT_EQ(stats.no_color, 6 * 120);
  EXPECT_EQ(static_cast<int64_t>(cloud.points_camera->size()), 160 * 120 - 6 * 120);
  int shifted_blue = 0;
  float min_x = 1e9f;
  for (const ColorPoint& p : *cloud.points_camera) {
    min_x = std::min(min_x, p.x);
    if (std::abs(p.x) < 1e-3) continue;  // On the colour seam.
    EXPECT_EQ(p.r, p.x < 0 ? 255 : 0) << "x=" << p.x;
    EXPECT_EQ(p.b, p.x < 0 ? 0 : 255) << "x=" << p.x;
    // Left of the depth camera's axis but right of the colour camera's: blue only if the
    // extrinsic was applied.
    if (p.x > 0.0f && p.x < 0.1f) ++shifted_blue;
  }
  EXPECT_GT(shifted_blue, 120 * 4);
  // Leftmost depth column: x_depth = -79.5 * 2 / 120 = -1.325 m, plus the 0.1 m offset.
  EXPECT_NEAR(min_x, -1.225, 1e-4);
}

TEST(FrameCloudTest, RangeGateDropsNearAndFar) {
  sensor::RgbdFrame frame = WallFrame(3000);
  for (int row = 0; row < 40; ++row) {
    for (int col = 0; col < 160; ++col) frame.depth_mm[row * 160 + col] = 100;
  }
  for (int row = 80; row < 120; ++row) {
    for (int col = 0; col < 160; ++col) frame.depth_mm[row * 160 + col] = 6000;
  }
  frame.depth_mm[40 * 160] = 0;  // One pixel with no measurement.
  FrameCloudStats stats;
  const CameraCloud cloud = BuildFrameCloud(frame, NoFilters(), &stats);
  EXPECT_EQ(stats.valid_depth, 160 * 120 - 1);
  EXPECT_EQ(stats.out_of_range, 2 * 40 * 160);
  EXPECT_EQ(static_cast<int64_t>(cloud.points_camera->size()), 40 * 160 - 1);
  for (const ColorPoint& p : *cloud.points_camera) EXPECT_NEAR(p.z, 3.0, 1e-5);
}

TEST(FrameCloudTest, VoxelGridBoundsPointsPerArea) {
  const sensor::RgbdFrame frame = WallFrame(2000);
  FrameCloudOptions options = NoFilters();
  options.voxel_size_m = 0.05;
  FrameCloudStats stats;
  const CameraCloud cloud = BuildFrameCloud(frame, options, &stats);
  // Wall seen: 160 x 120 pixels of 2/120 m = 2.667 m x 2.0 m; one point per 5 cm cell.
  const double expected = (160.0 * 2.0 / 120.0) * (120.0 * 2.0 / 120.0) / (0.05 * 0.05);
  EXPECT_EQ(stats.registered, 160 * 120);
  EXPECT_NEAR(static_cast<double>(stats.after_voxel), expected, 0.15 * expected);
  EXPECT_EQ(stats.after_voxel, static_cast<int64_t>(cloud.points_camera->size()));
}

TEST(FrameCloudTest, IsolatedOutlierIsRemoved) {
  sensor::RgbdFrame frame = WallFrame(2000);
  frame.depth_mm[60 * 160 + 80] = 4000;  // A lone return 2 m behind the wall.
  auto far_points = [](const CameraCloud& cloud) {
    int n = 0;
    for (const ColorPoint& p : *cloud.points_camera) n += p.z > 3.0f ? 1 : 0;
    return n;
  };
  FrameCloudOptions options;
  options.outlier_mean_k = 0;
  EXPECT_EQ(far_points(BuildFrameCloud(frame, options, nullptr)), 1);
  options.outlier_mean_k = 20;
  FrameCloudStats stats;
  const CameraCloud cloud = BuildFrameCloud(frame, options, &stats);
  EXPECT_EQ(far_points(cloud), 0);
  EXPECT_LT(stats.after_outlier, stats.after_voxel);
  // The wall itself survives (at most the image border is thinned).
  EXPECT_GT(stats.after_outlier, stats.after_voxel * 9 / 10);
}

TEST(FrameCloudTest, EmptyOrInconsistentFrameGivesEmptyCloud) {
  FrameCloudStats stats;
  const CameraCloud empty = BuildFrameCloud(sensor::RgbdFrame(), FrameCloudOptions(), &stats);
  ASSERT_NE(empty.points_camera, nullptr);
  EXPECT_TRUE(empty.points_camera->empty());
  EXPECT_EQ(stats.input_pixels, 0);

  sensor::RgbdFrame truncated = WallFrame(2000);
  truncated.depth_mm.resize(100);  // Buffer shorter than the intrinsics claim.
  EXPECT_TRUE(BuildFrameCloud(truncated, FrameCloudOptions(), &stats).points_camera->empty());
}

TEST(FrameCloudTest, OptionsValidationAndParsing) {
  FrameCloudOptions options;
  std::string error;
  EXPECT_TRUE(options.IsValid(&error));
  options.max_range_m = 0.1;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("max_range_m"), std::string::npos);

  auto reader = common::ConfigReader::FromString(
      "voxel_size_m: 0.05\noutlier_mean_k: 0\npixel_stride: 2\n", "test", &error);
  ASSERT_NE(reader, nullptr) << error;
  const FrameCloudOptions parsed = ParseFrameCloudOptions(*reader);
  EXPECT_TRUE(reader->Finish(&error)) << error;
  EXPECT_DOUBLE_EQ(parsed.voxel_size_m, 0.05);
  EXPECT_EQ(parsed.outlier_mean_k, 0);
  EXPECT_EQ(parsed.pixel_stride, 2);

  auto bad = common::ConfigReader::FromString("pixel_stride: 0\n", "bad.yaml", &error);
  ParseFrameCloudOptions(*bad);
  EXPECT_FALSE(bad->Finish(&error));
  EXPECT_NE(error.find("pixel_stride"), std::string::npos);
}

TEST(FrameCloudTest, RegisteredDepthImageCoversTheColourPixelsDepthLandsOn) {
  sensor::RgbdFrame frame = WallFrame(2000);
  // Same camera for both: every colour pixel gets its own depth.
  frame.depth_intrinsics = frame.color_intrinsics;
  frame.depth_mm.assign(320 * 240, 2000);
  frame.depth_mm[5 * 320 + 7] = 0;  // a hole stays a hole
  std::vector<float> depth_m = RegisterDepthImage(frame, 0.2, 5.5);
  ASSERT_EQ(depth_m.size(), 320u * 240u);
  EXPECT_FLOAT_EQ(depth_m[0], 2.0f);
  EXPECT_FLOAT_EQ(depth_m[5 * 320 + 7], 0.0f);
  EXPECT_FLOAT_EQ(depth_m[239 * 320 + 319], 2.0f);
  // Out of range: nothing registered.
  depth_m = RegisterDepthImage(frame, 0.2, 1.5);
  EXPECT_FLOAT_EQ(depth_m[100 * 320 + 100], 0.0f);
  // The low-resolution depth camera of WallFrame covers every other colour pixel.
  const sensor::RgbdFrame wall = WallFrame(2000);
  depth_m = RegisterDepthImage(wall, 0.2, 5.5);
  ASSERT_EQ(depth_m.size(), 320u * 240u);
  int covered = 0;
  for (float z : depth_m) covered += z > 0.0f;
  EXPECT_EQ(covered, 160 * 120);
  // No images: empty.
  EXPECT_TRUE(RegisterDepthImage(sensor::RgbdFrame(), 0.2, 5.5).empty());
}

}  // namespace
}  // namespace cloud
}  // namespace fusemap
