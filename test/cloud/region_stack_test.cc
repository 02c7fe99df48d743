#include "region_stack.h"

#include <gtest/gtest.h>

namespace fusemap {
namespace cloud {
namespace {

using common::Rigid3d;

ColorCloud MakePoints(const std::vector<Eigen::Vector3f>& points, uint8_t red) {
  ColorCloud cloud;
  for (const Eigen::Vector3f& p : points) {
    ColorPoint point;
    point.getVector3fMap() = p;
    point.r = red;
    point.g = point.b = 0;
    cloud.push_back(point);
  }
  return cloud;
}

TEST(RegionStackTest, MergesPointsOfOneVoxelIntoTheirMeanAndCountsFrames) {
  RegionStack region(0.1, Rigid3d(Eigen::Vector3d(1.0, 0.0, 0.0), Eigen::Quaterniond::Identity()));
  std::vector<uint32_t> new_slots;
  region.Insert(MakePoints({{0.01f, 0.01f, 0.01f}, {0.03f, 0.05f, 0.07f}, {0.5f, 0.5f, 0.5f}}, 100),
                Rigid3d::Identity(), 0, &new_slots);
  EXPECT_EQ(new_slots.size(), 2u);
  new_slots.clear();
  region.Insert(MakePoints({{0.05f, 0.03f, 0.01f}}, 200), Rigid3d::Identity(), 1, &new_slots);
  EXPECT_TRUE(new_slots.empty());
  ASSERT_EQ(region.num_alive(), 2u);
  const RegionVoxel& voxel = region.voxels()[0];
  EXPECT_EQ(voxel.num_points, 3u);
  EXPECT_EQ(voxel.hits, 2);  // frames, not points
  EXPECT_NEAR((voxel.mean_submap - Eigen::Vector3f(0.03f, 0.03f, 0.03f)).norm(), 0.f, 1e-6f);
  EXPECT_NEAR(voxel.mean_rgb.x(), 400.f / 3.f, 1e-3f);
  EXPECT_NEAR(region.map_cloud()[0].x, 1.03f, 1e-6f);
  EXPECT_EQ(region.map_cloud()[0].r, 133);
}

TEST(RegionStackTest, CarveRuleNeedsAsManyCarvingFramesAsHitFrames) {
  RegionStack region(0.1, Rigid3d::Identity());
  region.Insert(MakePoints({{0.05f, 0.05f, 0.05f}}, 0), Rigid3d::Identity(), 0, nullptr);
  region.Insert(MakePoints({{0.05f, 0.05f, 0.05f}}, 0), Rigid3d::Identity(), 1, nullptr);
  EXPECT_FALSE(region.Carve(0, 1));  // the frame that saw it cannot carve it
  EXPECT_FALSE(region.Carve(0, 2));
  EXPECT_FALSE(region.Carve(0, 2));  // one carve per frame
  EXPECT_TRUE(region.Carve(0, 3));
  const ColorPoint removed = region.Remove(0);
  EXPECT_NEAR(removed.x, 0.05f, 1e-6f);
  EXPECT_EQ(region.num_alive(), 0u);
  EXPECT_FALSE(std::isfinite(region.map_cloud()[0].x));
  // The voxel can be observed again: a new slot.
  std::vector<uint32_t> new_slots;
  region.Insert(MakePoints({{0.05f, 0.05f, 0.05f}}, 0), Rigid3d::Identity(), 4, &new_slots);
  EXPECT_EQ(new_slots, std::vector<uint32_t>{1});
}

TEST(RegionStackTest, ReleasedKeyIndexIsRebuiltOnInsert) {
  RegionStack region(0.1, Rigid3d::Identity());
  region.Insert(MakePoints({{0.05f, 0.05f, 0.05f}, {0.35f, 0.05f, 0.05f}}, 0), Rigid3d::Identity(),
                0, nullptr);
  region.ReleaseKeyIndex();
  EXPECT_FALSE(region.has_key_index());
  const size_t released_bytes = region.MemoryBytes();
  std::vector<uint32_t> new_slots;
  region.Insert(MakePoints({{0.06f, 0.05f, 0.05f}}, 0), Rigid3d::Identity(), 1, &new_slots);
  EXPECT_TRUE(region.has_key_index());
  EXPECT_TRUE(new_slots.empty());
  EXPECT_EQ(region.voxels()[0].num_points, 2u);
  EXPECT_GT(region.MemoryBytes(), released_bytes);
}

TEST(RegionStackTest, SetPoseMovesEveryLivePoint) {
  RegionStack region(0.05, Rigid3d::Identity());
  region.Insert(MakePoints({{1.f, 0.f, 0.f}, {0.f, 2.f, 0.f}}, 0), Rigid3d::Identity(), 0, nullptr);
  const Rigid3d T_map_submap(
      Eigen::Vector3d(0.0, 0.0, 1.0),
      Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ())));
  EXPECT_EQ(region.SetPose(T_map_submap), 2u);
  EXPECT_NEAR((region.map_cloud()[0].getVector3fMap() - Eigen::Vector3f(0.f, 1.f, 1.f)).norm(), 0.f,
              1e-5f);
  EXPECT_NEAR((region.map_cloud()[1].getVector3fMap() - Eigen::Vector3f(-2.f, 0.f, 1.f)).norm(),
              0.f, 1e-5f);
  EXPECT_NEAR((region.CenterInMap(0) - Eigen::Vector3f(-0.025f, 1.025f, 1.025f)).norm(), 0.f,
              1e-5f);
}

TEST(RegionStackTest, AddHitMergesLikeInsertAndRefreshesTheMapPoint) {
  const Rigid3d T_map_submap(Eigen::Vector3d(1.0, 0.0, 0.0), Eigen::Quaterniond::Identity());
  RegionStack by_insert(0.1, T_map_submap);
  RegionStack by_hit(0.1, T_map_submap);
  const ColorCloud first = MakePoints({{0.01f, 0.01f, 0.01f}}, 100);
  by_insert.Insert(first, Rigid3d::Identity(), 0, nullptr);
  by_hit.Insert(first, Rigid3d::Identity(), 0, nullptr);
  const std::vector<Eigen::Vector3f> later = {{0.05f, 0.03f, 0.01f}, {0.09f, 0.08f, 0.07f}};
  by_insert.Insert(MakePoints(later, 200), Rigid3d::Identity(), 3, nullptr);
  for (const Eigen::Vector3f& p : later) by_hit.AddHit(0, p, Eigen::Vector3f(200.f, 0.f, 0.f), 3);
  ASSERT_EQ(by_hit.num_alive(), 1u);
  const RegionVoxel& a = by_insert.voxels()[0];
  const RegionVoxel& b = by_hit.voxels()[0];
  EXPECT_EQ(b.num_points, 3u);
  EXPECT_EQ(b.hits, 2);  // two points of frame 3 count once
  EXPECT_EQ(b.hits, a.hits);
  EXPECT_EQ(b.last_hit_frame, 3);
  EXPECT_NEAR((b.mean_submap - a.mean_submap).norm(), 0.f, 1e-6f);
  EXPECT_NEAR(b.mean_rgb.x(), 500.f / 3.f, 1e-3f);
  EXPECT_NEAR(by_hit.map_cloud()[0].x, 1.f + b.mean_submap.x(), 1e-6f);
  EXPECT_EQ(by_hit.map_cloud()[0].r, 167);
}

}  // namespace
}  // namespace cloud
}  // namespace fusemap
