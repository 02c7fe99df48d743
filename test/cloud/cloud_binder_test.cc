#include "fusemap/cloud/cloud_binder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
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

// A 2 m x 2 m wall 2 m in front of the camera, sampled every 1 cm, with 4 mm noise.
std::vector<Eigen::Vector3f> NoisyWall(std::mt19937* rng) {
  std::uniform_real_distribution<float> jitter(-0.004f, 0.004f);
  std::vector<Eigen::Vector3f> points;
  for (int i = 0; i < 200; ++i) {
    for (int j = 0; j < 200; ++j) {
      points.emplace_back(-1.f + 0.01f * i + jitter(*rng), -1.f + 0.01f * j + jitter(*rng),
                          2.0f + jitter(*rng));
    }
  }
  return points;
}

// Lap 1 binds the wall to submap 0, lap 2 (same camera pose in the map) to submap 5, whose pose
// is T_map_submap5. Returns points stored after lap 1.
size_t BindWallTwice(CloudBinder* binder, const Rigid3d& T_map_submap5) {
  std::mt19937 rng(11);
  const Rigid3d T_map_camera = Pose(0.3, -0.2, 0.4, 0.2);
  binder->SetSubmapPose(0, Rigid3d::Identity());
  binder->SetSubmapPose(5, T_map_submap5);
  binder->AddCloud(0, T_map_camera, MakeCloud(NoisyWall(&rng)));
  const size_t after_first = binder->stats().points_stored;
  binder->AddCloud(5, T_map_submap5.inverse() * T_map_camera,
                   MakeCloud(NoisyWall(&rng), 0, 0, 200));
  return after_first;
}

TEST(CloudBinderTest, RevisitedWallMergesIntoTheFirstRegionOnlyWithMergeRevisits) {
  // Same map pose for both submaps, then a submap 5 rotated and shifted against submap 0 (its
  // voxel grid is not aligned with region 0's).
  for (const Rigid3d& T_map_submap5 : {Rigid3d::Identity(), Pose(0.77, -0.31, 0.0, 0.61)}) {
    CloudBinderOptions options;
    CloudBinder baseline(options);
    const size_t baseline_first = BindWallTwice(&baseline, T_map_submap5);
    const double baseline_ms = baseline.stats().last_frame_ms;
    options.merge_revisits = true;
    // Submap 5 is beyond the carve window of submap 0: by default a wall seen in one frame is
    // not yet established enough to take its hits.
    CloudBinder cautious(options);
    BindWallTwice(&cautious, T_map_submap5);
    EXPECT_EQ(cautious.stats().points_merged_into_other_regions, 0);
    options.merge_min_hits_beyond_window = 1;
    CloudBinder binder(options);
    const size_t first = BindWallTwice(&binder, T_map_submap5);
    ASSERT_EQ(first, baseline_first);
    ASSERT_GT(first, 3000u);
    // Without merging, lap 2 stores the wall again.
    EXPECT_GT(baseline.stats().points_stored, 1.9 * baseline_first);
    EXPECT_EQ(baseline.stats().points_merged_into_other_regions, 0);
    // With merging, lap 2 adds under 3 % new voxels (noise reaching cells lap 1 left empty).
    EXPECT_LT(binder.stats().points_stored, 1.03 * first);
    EXPECT_LT(binder.RegionCloud(5)->size(), 0.03 * first);
    EXPECT_GT(binder.stats().points_merged_into_other_regions, 0.97 * 200 * 200);
    EXPECT_EQ(binder.stats().points_stored, binder.GlobalCloud()->size());
    // Merged voxels count lap 2 as a hit and average its colour (red then blue).
    std::vector<uint16_t> hits;
    const ColorCloud::Ptr global = binder.GlobalCloud(&hits);
    size_t seen_twice = 0;
    double blue_sum = 0.0;
    for (size_t i = 0; i < hits.size(); ++i) {
      seen_twice += hits[i] == 2 ? 1 : 0;
      blue_sum += global->points[i].b;
    }
    EXPECT_GT(seen_twice, 0.9 * hits.size());
    EXPECT_NEAR(blue_sum / hits.size(), 125.0, 10.0);  // (50 + 200) / 2
    std::printf("[ timing   ] lap-2 AddCloud of %d points: %.2f ms without, %.2f ms with merge "
                "(search and merge %.2f ms); stored %zu after lap 1, after lap 2 %zu without, "
                "%zu with\n",
                200 * 200, baseline_ms, binder.stats().last_frame_ms, binder.stats().last_merge_ms,
                first, baseline.stats().points_stored, binder.stats().points_stored);
  }
}

TEST(CloudBinderTest, MergedVoxelsMoveWithTheirOriginalRegion) {
  CloudBinderOptions options;
  options.merge_revisits = true;
  options.merge_min_hits_beyond_window = 1;
  CloudBinder binder(options);
  const Rigid3d T_map_submap5 = Pose(0.5, 0.5, 0.0, -0.4);
  BindWallTwice(&binder, T_map_submap5);
  const size_t region0_size = binder.RegionCloud(0)->size();
  const ColorCloud::Ptr region5_before = binder.RegionCloud(5);

  // Loop closure moves submap 0 only: the merged lap-2 points go with it.
  const Rigid3d T_map_submap0 = Pose(-2.0, 1.0, 0.1, 1.2);
  binder.OnSubmapsMoved({{0, T_map_submap0}});
  EXPECT_EQ(binder.stats().last_update_points, region0_size);
  const ColorCloud::Ptr region0 = binder.RegionCloud(0);
  ASSERT_EQ(region0->size(), region0_size);
  const Rigid3d T_camera_map = (T_map_submap0 * Pose(0.3, -0.2, 0.4, 0.2)).inverse();
  for (const ColorPoint& p : region0->points) {
    const Eigen::Vector3d p_camera = T_camera_map * p.getVector3fMap().cast<double>();
    // Voxel means of the wall: within the noise in depth, inside the wall's extent.
    ASSERT_NEAR(p_camera.z(), 2.0, 0.005);
    ASSERT_LE(p_camera.head<2>().cwiseAbs().maxCoeff(), 1.01);
  }
  const ColorCloud::Ptr region5_after = binder.RegionCloud(5);
  ASSERT_EQ(region5_after->size(), region5_before->size());
  for (size_t i = 0; i < region5_after->size(); ++i) {
    EXPECT_EQ(region5_after->points[i].getVector3fMap(),
              region5_before->points[i].getVector3fMap());
  }
  // A third visit at the moved pose of submap 0 merges into region 0 again (index re-posed).
  std::mt19937 rng(5);
  const int64_t merged_before = binder.stats().points_merged_into_other_regions;
  binder.SetSubmapPose(9, Rigid3d::Identity());
  binder.AddCloud(9, T_map_submap0 * Pose(0.3, -0.2, 0.4, 0.2), MakeCloud(NoisyWall(&rng)));
  EXPECT_GT(binder.stats().points_merged_into_other_regions - merged_before, 0.97 * 200 * 200);
  EXPECT_LT(binder.RegionCloud(9)->size(), 0.03 * region0_size);
}

TEST(CloudBinderTest, MergeRevisitsWorksWithoutDynamicRemovalAndParses) {
  CloudBinderOptions options;
  options.remove_dynamic = false;
  options.merge_revisits = true;
  options.merge_min_hits_beyond_window = 1;
  CloudBinder binder(options);
  const size_t first = BindWallTwice(&binder, Pose(0.1, 0.2, 0.0, 0.3));
  EXPECT_LT(binder.stats().points_stored, 1.03 * first);

  std::string error;
  auto reader = common::ConfigReader::FromString(
      "merge_revisits: true\nmerge_min_hits_beyond_window: 2\n", "test", &error);
  ASSERT_NE(reader, nullptr) << error;
  const CloudBinderOptions parsed = ParseCloudBinderOptions(*reader);
  EXPECT_TRUE(parsed.merge_revisits);
  EXPECT_EQ(parsed.merge_min_hits_beyond_window, 2);
  EXPECT_TRUE(reader->Finish(&error)) << error;
  EXPECT_FALSE(CloudBinderOptions().merge_revisits);
}

}  // namespace
}  // namespace cloud
}  // namespace fusemap
