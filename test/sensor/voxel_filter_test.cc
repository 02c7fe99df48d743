#include "fusemap/sensor/voxel_filter.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fusemap {
namespace sensor {
namespace {

TEST(VoxelFilterTest, KeepsFirstPointPerVoxel) {
  // Voxels of 1 m: (0,0) gets three points, (1,0) one, (-1,-1) two, (0,2) one.
  const PointCloud2d points = {{0.1f, 0.1f}, {0.9f, 0.2f}, {1.5f, 0.5f},  {0.5f, 0.99f},
                               {-0.5f, -0.5f}, {-0.1f, -0.9f}, {0.2f, 2.3f}};
  const PointCloud2d filtered = VoxelFilter(points, 1.f);
  ASSERT_EQ(filtered.size(), 4u);
  EXPECT_EQ(filtered[0], points[0]);
  EXPECT_EQ(filtered[1], points[2]);
  EXPECT_EQ(filtered[2], points[4]);
  EXPECT_EQ(filtered[3], points[6]);
}

TEST(VoxelFilterTest, DenseLineCountMatchesVoxelCount) {
  // 1000 points on [0, 10) m along x, filtered at 0.5 m -> 20 voxels.
  PointCloud2d points;
  for (int i = 0; i < 1000; ++i) points.emplace_back(0.01f * i + 0.005f, 0.25f);
  EXPECT_EQ(VoxelFilter(points, 0.5f).size(), 20u);
  EXPECT_EQ(VoxelFilter(points, 0.001f).size(), 1000u);
}

TEST(VoxelFilterTest, RangeDataFiltersReturnsAndMissesSeparately) {
  RangeData data;
  data.origin = Eigen::Vector2f(3.f, 4.f);
  data.returns = {{0.1f, 0.1f}, {0.2f, 0.2f}};
  data.misses = {{0.15f, 0.15f}};
  const RangeData filtered = VoxelFilter(data, 1.f);
  EXPECT_EQ(filtered.returns.size(), 1u);
  EXPECT_EQ(filtered.misses.size(), 1u);
  EXPECT_EQ(filtered.origin, data.origin);
}

PointCloud2d Circle(int n, float radius_m) {
  PointCloud2d points;
  for (int i = 0; i < n; ++i) {
    const float a = 2.f * static_cast<float>(M_PI) * i / n;
    points.emplace_back(radius_m * std::cos(a), radius_m * std::sin(a));
  }
  return points;
}

TEST(AdaptiveVoxelFilterTest, KeepsAtLeastMinNumPointsAndFilters) {
  // 2000 points on a 5 m circle: 0.5 m voxels leave far fewer than 200 (~ 2*pi*5/0.5*1.3).
  const PointCloud2d points = Circle(2000, 5.f);
  AdaptiveVoxelFilterOptions options;
  options.max_length_m = 0.5f;
  options.min_num_points = 200;
  ASSERT_LT(VoxelFilter(points, options.max_length_m).size(), 200u);
  const PointCloud2d filtered = AdaptiveVoxelFilter(points, options);
  EXPECT_GE(filtered.size(), 200u);
  // Bisection to 10 % of the edge length keeps the count well below the input size.
  EXPECT_LT(filtered.size(), 400u);
}

TEST(AdaptiveVoxelFilterTest, UsesMaxLengthWhenAlreadyDenseEnough) {
  const PointCloud2d points = Circle(2000, 5.f);
  AdaptiveVoxelFilterOptions options;
  options.max_length_m = 0.5f;
  options.min_num_points = 10;
  EXPECT_EQ(AdaptiveVoxelFilter(points, options).size(),
            VoxelFilter(points, options.max_length_m).size());
}

TEST(AdaptiveVoxelFilterTest, DropsFarPointsAndKeepsSmallClouds) {
  PointCloud2d points = Circle(50, 5.f);
  points.emplace_back(100.f, 0.f);
  AdaptiveVoxelFilterOptions options;
  options.max_range_m = 10.f;
  options.min_num_points = 200;
  const PointCloud2d filtered = AdaptiveVoxelFilter(points, options);
  EXPECT_EQ(filtered.size(), 50u);
  for (const auto& p : filtered) EXPECT_LE(p.norm(), 10.f);
}

}  // namespace
}  // namespace sensor
}  // namespace fusemap
