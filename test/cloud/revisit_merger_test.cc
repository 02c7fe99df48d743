#include "revisit_merger.h"

#include <gtest/gtest.h>

#include "region_stack.h"

namespace fusemap {
namespace cloud {
namespace {

using common::Rigid3d;

constexpr double kVoxelM = 0.1;

Rigid3d Pose(double x, double y, double yaw_rad) {
  return Rigid3d(Eigen::Vector3d(x, y, 0.0),
                 Eigen::Quaterniond(Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ())));
}

// Regions with one point each at the given submap-frame positions, indexed like CloudBinder.
struct Fixture {
  std::map<int, std::unique_ptr<RegionStack>> regions;
  MapBlockIndex index{kVoxelM, 4};

  RegionStack& Add(int id, const Rigid3d& T_map_submap,
                   const std::vector<Eigen::Vector3f>& points_submap, int frames = 1) {
    auto& region = regions[id];
    region.reset(new RegionStack(kVoxelM, T_map_submap));
    ColorCloud cloud;
    for (const Eigen::Vector3f& p : points_submap) {
      ColorPoint point;
      point.getVector3fMap() = p;
      cloud.push_back(point);
    }
    std::vector<uint32_t> slots;
    for (int frame = 0; frame < frames; ++frame) {
      region->Insert(cloud, Rigid3d::Identity(), frame, &slots);
    }
    for (const uint32_t slot : slots) index.Add(id, slot, region->CenterInMap(slot));
    return *region;
  }
};

TEST(RevisitMergerTest, FindsTheVoxelOfAnotherRegionInItsOwnRotatedGrid) {
  Fixture f;
  const Rigid3d T_map_submap = Pose(1.23, -0.47, 0.7);
  // Region 3: voxels (in its grid) around a few submap points.
  f.Add(3, T_map_submap, {{0.05f, 0.05f, 0.05f}, {0.55f, 0.25f, 0.15f}, {2.05f, 1.05f, 0.35f}});
  // Points anywhere inside region 3's cells (near their corners too), plus misses.
  const std::vector<Eigen::Vector3f> inside_submap = {
      {0.001f, 0.099f, 0.002f}, {0.51f, 0.29f, 0.19f}, {2.099f, 1.001f, 0.399f}};
  std::vector<Eigen::Vector3f> points_map;
  for (const Eigen::Vector3f& p : inside_submap) {
    points_map.push_back((T_map_submap * p.cast<double>()).cast<float>());
  }
  points_map.push_back((T_map_submap * Eigen::Vector3d(0.15, 0.05, 0.05)).cast<float>());
  points_map.push_back(Eigen::Vector3f(10.f, 10.f, 0.f));
  // The frame's own region 8 holds the place of point 1 too: never a match for its own frames.
  f.Add(8, Rigid3d::Identity(), {points_map[1]});

  const std::vector<RevisitMatch> matches =
      FindRevisitedVoxels(points_map, 8, {}, f.index, f.regions);
  ASSERT_EQ(matches.size(), 3u);
  for (uint32_t i = 0; i < 3; ++i) {
    EXPECT_EQ(matches[i].point, i);
    EXPECT_EQ(matches[i].voxel.region, 3);
    EXPECT_EQ(matches[i].voxel.slot, i);
    EXPECT_NEAR((matches[i].p_submap - inside_submap[i]).norm(), 0.f, 1e-5f);
  }
  // Seen from region 3, the point in region 8's voxel matches region 8.
  const std::vector<RevisitMatch> from3 =
      FindRevisitedVoxels(points_map, 3, {}, f.index, f.regions);
  ASSERT_EQ(from3.size(), 1u);
  EXPECT_EQ(from3[0].point, 1u);
  EXPECT_EQ(from3[0].voxel.region, 8);
}

TEST(RevisitMergerTest, PrefersTheMostObservedVoxelAndSkipsRemovedOnes) {
  Fixture f;
  const Eigen::Vector3f p(0.35f, 0.35f, 0.35f);
  f.Add(1, Rigid3d::Identity(), {p}, 2);
  f.Add(2, Pose(0.0, 0.0, 0.05), {p}, 5);
  f.Add(4, Pose(0.01, 0.0, 0.0), {p}, 3);
  std::vector<RevisitMatch> matches = FindRevisitedVoxels({p}, 0, {}, f.index, f.regions);
  ASSERT_EQ(matches.size(), 1u);
  EXPECT_EQ(matches[0].voxel.region, 2);
  f.regions.at(2)->Remove(0);
  matches = FindRevisitedVoxels({p}, 0, {}, f.index, f.regions);
  ASSERT_EQ(matches.size(), 1u);
  EXPECT_EQ(matches[0].voxel.region, 4);
  f.regions.at(4)->Remove(0);
  f.regions.at(1)->Remove(0);
  EXPECT_TRUE(FindRevisitedVoxels({p}, 0, {}, f.index, f.regions).empty());
}

TEST(RevisitMergerTest, RegionsBeyondTheCarveWindowNeedEstablishedVoxels) {
  Fixture f;
  const Eigen::Vector3f p(0.35f, 0.35f, 0.35f);
  f.Add(1, Rigid3d::Identity(), {p}, 2);  // 9 ids from the frame's region 10
  RevisitMergeOptions options;
  options.carve_window = 2;
  options.min_hits_beyond_window = 3;
  EXPECT_TRUE(FindRevisitedVoxels({p}, 10, options, f.index, f.regions).empty());
  EXPECT_EQ(FindRevisitedVoxels({p}, 3, options, f.index, f.regions).size(), 1u);  // within
  f.regions.at(1)->AddHit(0, p, Eigen::Vector3f::Zero(), 7);
  EXPECT_EQ(FindRevisitedVoxels({p}, 10, options, f.index, f.regions).size(), 1u);
}

}  // namespace
}  // namespace cloud
}  // namespace fusemap
