#include "free_space_carver.h"

#include <gtest/gtest.h>

namespace fusemap {
namespace cloud {
namespace {

constexpr double kVoxel = 0.1;

// One ray along +x from the origin to (2, 0.05, 0.05); every voxel on the way is "occupied".
class FreeSpaceCarverTest : public ::testing::Test {
 protected:
  FreeSpaceCarverTest() : index_(kVoxel, 4) {
    for (int i = 0; i < 30; ++i) index_.Add(0, i, Eigen::Vector3f(0.1f * i + 0.05f, 0.05f, 0.05f));
    options_.voxel_size_m = kVoxel;
    options_.ray_stride = 1;
    options_.margin_voxels = 3;
    options_.margin_range_fraction = 0.0;
  }
  MapBlockIndex index_;
  FreeSpaceCarverOptions options_;
};

TEST_F(FreeSpaceCarverTest, CarvesStrictlyBeforeTheEndMinusTheMargin) {
  FreeSpaceCarver carver(options_);
  const auto carved = carver.CarvedVoxels(Eigen::Vector3f(0.05f, 0.05f, 0.05f),
                                          {Eigen::Vector3f(2.05f, 0.05f, 0.05f)}, index_, 0);
  // End voxel 20, margin 0.3 m: voxel centres up to x < 1.75, i.e. voxels 0..16, except those
  // within one voxel of the frame's own hit (19, 20, 21), which are beyond anyway.
  EXPECT_EQ(carved.size(), 17u);
  EXPECT_EQ(carved.count(PackVoxelKey(Eigen::Vector3i(16, 0, 0))), 1u);
  EXPECT_EQ(carved.count(PackVoxelKey(Eigen::Vector3i(17, 0, 0))), 0u);
}

TEST_F(FreeSpaceCarverTest, NeverCarvesNextToAPointTheSameFrameSaw) {
  FreeSpaceCarver carver(options_);
  // A second return of the same frame sits in voxel (5, 1, 0): voxels 4..6 on the ray stay.
  const auto carved = carver.CarvedVoxels(
      Eigen::Vector3f(0.05f, 0.05f, 0.05f),
      {Eigen::Vector3f(2.05f, 0.05f, 0.05f), Eigen::Vector3f(0.55f, 0.15f, 0.05f)}, index_, 0);
  EXPECT_EQ(carved.count(PackVoxelKey(Eigen::Vector3i(3, 0, 0))), 1u);
  for (int i = 4; i <= 6; ++i) EXPECT_EQ(carved.count(PackVoxelKey(Eigen::Vector3i(i, 0, 0))), 0u);
}

TEST_F(FreeSpaceCarverTest, MarginGrowsWithRangeAndEmptyBlocksAreSkipped) {
  options_.margin_range_fraction = 0.25;  // 0.5 m at 2 m range
  FreeSpaceCarver carver(options_);
  const auto carved = carver.CarvedVoxels(Eigen::Vector3f(0.05f, 0.05f, 0.05f),
                                          {Eigen::Vector3f(2.05f, 0.05f, 0.05f)}, index_, 0);
  EXPECT_EQ(carved.size(), 15u);
  // A ray through space the index does not cover reports nothing.
  const auto none = carver.CarvedVoxels(Eigen::Vector3f(0.05f, 5.05f, 0.05f),
                                        {Eigen::Vector3f(2.05f, 5.05f, 0.05f)}, index_, 0);
  EXPECT_TRUE(none.empty());
}

}  // namespace
}  // namespace cloud
}  // namespace fusemap
