#include "depth_carver.h"

#include <gtest/gtest.h>

#include <vector>

#include "fusemap/cloud/cloud_binder.h"

namespace fusemap {
namespace cloud {
namespace {

sensor::PinholeIntrinsics SmallCamera() {
  sensor::PinholeIntrinsics k;
  k.width = 64;
  k.height = 48;
  k.fx = k.fy = 50.0;
  k.cx = 31.5;
  k.cy = 23.5;
  return k;
}

// A fronto-parallel wall at `wall_mm`; columns [hole_begin, hole_end) return nothing.
std::vector<uint16_t> WallImage(uint16_t wall_mm, int hole_begin = 0, int hole_end = 0) {
  const sensor::PinholeIntrinsics k = SmallCamera();
  std::vector<uint16_t> depth(k.width * k.height, wall_mm);
  for (int row = 0; row < k.height; ++row) {
    for (int col = hole_begin; col < hole_end; ++col) depth[row * k.width + col] = 0;
  }
  return depth;
}

TEST(DepthCarverTest, SeesThroughOnlyClearlyInFrontOfTheSurface) {
  DepthCarver carver{DepthCarverOptions()};  // margin max(0.09 m, 5 %)
  carver.SetImage(SmallCamera(), WallImage(4000));
  EXPECT_TRUE(carver.SeesThrough(Eigen::Vector3f(0.f, 0.f, 2.0f)));
  EXPECT_TRUE(carver.SeesThrough(Eigen::Vector3f(0.f, 0.f, 3.7f)));
  EXPECT_FALSE(carver.SeesThrough(Eigen::Vector3f(0.f, 0.f, 3.85f)));  // within 0.2 m margin
  EXPECT_FALSE(carver.SeesThrough(Eigen::Vector3f(0.f, 0.f, 4.0f)));   // on the wall
  EXPECT_FALSE(carver.SeesThrough(Eigen::Vector3f(0.f, 0.f, 4.5f)));   // behind it
  EXPECT_FALSE(carver.SeesThrough(Eigen::Vector3f(5.f, 0.f, 2.0f)));   // outside the image
  EXPECT_FALSE(carver.SeesThrough(Eigen::Vector3f(0.f, 0.f, -1.f)));   // behind the camera
}

TEST(DepthCarverTest, NearestDepthInTheWindowProtectsEdges) {
  // Left half at 2 m (a box edge at column 32), right half at 4 m.
  const sensor::PinholeIntrinsics k = SmallCamera();
  std::vector<uint16_t> depth = WallImage(4000);
  for (int row = 0; row < k.height; ++row) {
    for (int col = 0; col < 32; ++col) depth[row * k.width + col] = 2000;
  }
  DepthCarverOptions options;
  options.pixel_stride = 2;
  options.window_cells = 1;
  DepthCarver carver(options);
  carver.SetImage(k, depth);
  // A point of the box edge projecting just right of it must compare against the box.
  EXPECT_FALSE(carver.SeesThrough(Eigen::Vector3f(0.02f, 0.f, 2.0f)));
  // Well inside the background it is free space in front of the 4 m wall.
  EXPECT_TRUE(carver.SeesThrough(Eigen::Vector3f(0.4f, 0.f, 2.0f)));
}

TEST(DepthCarverTest, NoReturnCarvesOnlyUpToItsLimit) {
  DepthCarverOptions options;
  options.no_return_carve_m = 3.0;
  DepthCarver carver(options);
  carver.SetImage(SmallCamera(), WallImage(4000, 0, 64));  // nothing returns
  EXPECT_TRUE(carver.SeesThrough(Eigen::Vector3f(0.f, 0.f, 2.5f)));
  EXPECT_FALSE(carver.SeesThrough(Eigen::Vector3f(0.f, 0.f, 3.5f)));
}

TEST(DepthCarverTest, BinderRemovesAPersonSeenThroughAndKeepsTheWall) {
  CloudBinderOptions options;
  options.voxel_size_m = 0.05;
  CloudBinder binder(options);
  binder.SetSubmapPose(0, common::Rigid3d::Identity());
  // Camera at the origin looking along +z: a person patch at 2 m and the wall at 4 m.
  CameraCloud cloud;
  cloud.points_camera.reset(new ColorCloud);
  for (float x = -0.5f; x <= 0.5f; x += 0.05f) {
    for (float y = -0.4f; y <= 0.4f; y += 0.05f) {
      ColorPoint wall;
      wall.getVector3fMap() = Eigen::Vector3f(x * 4.f, y * 4.f, 4.f);
      cloud.points_camera->push_back(wall);
      if (std::abs(x) < 0.1f && std::abs(y) < 0.1f) {
        ColorPoint person;
        person.getVector3fMap() = Eigen::Vector3f(x, y, 2.f);
        cloud.points_camera->push_back(person);
      }
    }
  }
  binder.AddCloud(0, common::Rigid3d::Identity(), cloud);
  const size_t stored = binder.stats().points_stored;
  // The person left: the next image sees the wall everywhere.
  binder.CarveWithDepth(0, common::Rigid3d::Identity(), SmallCamera(), WallImage(4000));
  size_t person_left = 0, wall_left = 0;
  const ColorCloud::Ptr global = binder.GlobalCloud();
  for (const ColorPoint& p : global->points) {
    (p.z < 3.f ? person_left : wall_left) += 1;
  }
  EXPECT_EQ(person_left, 0u);
  EXPECT_EQ(wall_left + binder.removed_points().size(), stored);
  EXPECT_GT(binder.removed_points().size(), 0u);
  EXPECT_EQ(binder.stats().carve_frames, 1);
}

}  // namespace
}  // namespace cloud
}  // namespace fusemap
