#include "fusemap/cloud/cloud_binder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace fusemap {
namespace cloud {
namespace {

using common::Rigid3d;

Rigid3d Pose(double x, double y, double z, double yaw_rad) {
  return Rigid3d(Eigen::Vector3d(x, y, z),
                 Eigen::Quaterniond(Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ())));
}

CameraCloud MakeCloud(const std::vector<Eigen::Vector3f>& points, uint8_t r = 200, uint8_t g = 100,
                      uint8_t b = 50) {
  CameraCloud cloud;
  cloud.points_camera.reset(new ColorCloud);
  for (const Eigen::Vector3f& p : points) {
    ColorPoint point;
    point.getVector3fMap() = p;
    point.r = r;
    point.g = g;
    point.b = b;
    cloud.points_camera->push_back(point);
  }
  return cloud;
}

// A 10 x 10 grid of points 10 cm apart: each point in its own 3 cm voxel.
std::vector<Eigen::Vector3f> SparseGrid(float z_m) {
  std::vector<Eigen::Vector3f> points;
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 10; ++j) points.emplace_back(0.1f * i + 0.015f, 0.1f * j + 0.015f, z_m);
  }
  return points;
}

TEST(CloudBinderTest, CloudFollowsItsSubmapWhenTheSubmapMoves) {
  CloudBinder binder{CloudBinderOptions()};
  const Rigid3d T_map_submap = Pose(1.0, 2.0, 0.0, 0.3);
  const Rigid3d T_submap_camera = Pose(0.2, -0.1, 0.5, -0.7);
  binder.SetSubmapPose(7, T_map_submap);
  const std::vector<Eigen::Vector3f> points_camera = SparseGrid(1.5f);
  binder.AddCloud(7, T_submap_camera, MakeCloud(points_camera));

  auto check = [&](const Rigid3d& T_map_submap_now) {
    const ColorCloud::Ptr global = binder.GlobalCloud();
    ASSERT_EQ(global->size(), points_camera.size());
    for (size_t i = 0; i < points_camera.size(); ++i) {
      const Eigen::Vector3d expected =
          T_map_submap_now * (T_submap_camera * points_camera[i].cast<double>());
      EXPECT_NEAR((global->points[i].getVector3fMap().cast<double>() - expected).norm(), 0.0, 1e-4);
      EXPECT_EQ(global->points[i].r, 200);
    }
  };
  check(T_map_submap);
  const Rigid3d T_map_submap_moved = Pose(-3.0, 0.5, 0.1, 2.5);
  binder.OnSubmapsMoved({{7, T_map_submap_moved}});
  check(T_map_submap_moved);
  EXPECT_EQ(binder.stats().last_update_points, points_camera.size());
  EXPECT_EQ(binder.stats().last_update_regions, 1u);
}

TEST(CloudBinderTest, MovingOneRegionRebuildsOnlyThatRegion) {
  CloudBinder binder{CloudBinderOptions()};
  for (int id = 0; id < 10; ++id) {
    binder.SetSubmapPose(id, Pose(2.0 * id, 0.0, 0.0, 0.1 * id));
    binder.AddCloud(id, Rigid3d::Identity(), MakeCloud(SparseGrid(1.0f + 0.1f * id)));
  }
  const ColorCloud::Ptr untouched_before = binder.RegionCloud(5);
  const int64_t rebuilt_before = binder.stats().rebuilt_points_total;

  // Submap 42 has no clouds: remembered, costs nothing.
  binder.OnSubmapsMoved({{3, Pose(0.0, 5.0, 0.0, 1.0)}, {42, Pose(1.0, 1.0, 0.0, 0.0)}});

  EXPECT_EQ(binder.stats().last_update_regions, 1u);
  EXPECT_EQ(binder.stats().last_update_points, 100u);
  EXPECT_EQ(binder.stats().rebuilt_points_total - rebuilt_before, 100);
  const ColorCloud::Ptr untouched_after = binder.RegionCloud(5);
  ASSERT_EQ(untouched_after->size(), untouched_before->size());
  for (size_t i = 0; i < untouched_after->size(); ++i) {
    EXPECT_EQ(untouched_after->points[i].getVector3fMap(),
              untouched_before->points[i].getVector3fMap());
  }
  EXPECT_EQ(binder.GlobalCloud()->size(), 1000u);
  EXPECT_EQ(binder.stats().regions, 10u);
  // A later cloud bound to the remembered submap lands at its pose.
  binder.AddCloud(42, Rigid3d::Identity(), MakeCloud({Eigen::Vector3f(0.f, 0.f, 0.f)}));
  const ColorCloud::Ptr region = binder.RegionCloud(42);
  ASSERT_EQ(region->size(), 1u);
  EXPECT_NEAR(region->points[0].x, 1.0f, 1e-5f);
  EXPECT_NEAR(region->points[0].y, 1.0f, 1e-5f);
}

TEST(CloudBinderTest, RepeatedlyObservedWallIsBoundedByVoxelSizeAndAveragesColour) {
  CloudBinderOptions options;
  options.remove_dynamic = false;
  CloudBinder binder(options);
  binder.SetSubmapPose(0, Rigid3d::Identity());
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> jitter(-0.004f, 0.004f);
  const int kFrames = 20;
  for (int frame = 0; frame < kFrames; ++frame) {
    // A 2 m x 2 m wall 2 m in front of the camera, sampled every 1 cm, with depth noise.
    std::vector<Eigen::Vector3f> points;
    for (int i = 0; i < 200; ++i) {
      for (int j = 0; j < 200; ++j) {
        points.emplace_back(-1.f + 0.01f * i + jitter(rng), -1.f + 0.01f * j + jitter(rng),
                            2.0f + jitter(rng));
      }
    }
    const bool red = frame % 2 == 0;
    binder.AddCloud(0, Pose(0.0, 0.0, 0.0, 0.0),
                    MakeCloud(points, red ? 200 : 0, 0, red ? 0 : 200));
  }
  const double area_m2 = 4.0;
  const double voxel_area_m2 = options.voxel_size_m * options.voxel_size_m;
  const ColorCloud::Ptr global = binder.GlobalCloud();
  EXPECT_EQ(binder.stats().points_in, kFrames * 200 * 200);
  EXPECT_EQ(binder.stats().points_stored, global->size());
  // A plane not aligned with the grid straddles at most two voxel layers (jitter 4 mm).
  EXPECT_LE(global->size() / area_m2, 2.0 / voxel_area_m2);
  EXPECT_GE(global->size() / area_m2, 0.9 / voxel_area_m2);
  double red_sum = 0.0, blue_sum = 0.0;
  for (const ColorPoint& p : global->points) {
    red_sum += p.r;
    blue_sum += p.b;
  }
  EXPECT_NEAR(red_sum / global->size(), 100.0, 5.0);
  EXPECT_NEAR(blue_sum / global->size(), 100.0, 5.0);
  EXPECT_GT(binder.MemoryBytes(), global->size() * sizeof(ColorPoint));
}

TEST(CloudBinderTest, ParsesAndValidatesOptions) {
  std::string error;
  auto reader = common::ConfigReader::FromString(
      "voxel_size_m: 0.05\nremove_dynamic: false\ndynamic_ray_stride: 8\n"
      "dynamic_margin_voxels: 2\ndynamic_max_ray_length_m: 4.0\nindex_block_voxels: 4\n",
      "test", &error);
  ASSERT_NE(reader, nullptr) << error;
  const CloudBinderOptions options = ParseCloudBinderOptions(*reader);
  EXPECT_TRUE(reader->Finish(&error)) << error;
  EXPECT_DOUBLE_EQ(options.voxel_size_m, 0.05);
  EXPECT_FALSE(options.remove_dynamic);
  EXPECT_EQ(options.dynamic_ray_stride, 8);
  EXPECT_EQ(options.dynamic_margin_voxels, 2);
  EXPECT_DOUBLE_EQ(options.dynamic_max_ray_length_m, 4.0);
  EXPECT_EQ(options.index_block_voxels, 4);

  auto bad = common::ConfigReader::FromString("voxel_size_m: -1\n", "bad", &error);
  ASSERT_NE(bad, nullptr) << error;
  ParseCloudBinderOptions(*bad);
  EXPECT_FALSE(bad->Finish(&error));
  EXPECT_NE(error.find("voxel_size_m"), std::string::npos) << error;
  CloudBinderOptions invalid;
  invalid.dynamic_ray_stride = 0;
  EXPECT_FALSE(invalid.IsValid(&error));
}

}  // namespace
}  // namespace cloud
}  // namespace fusemap
