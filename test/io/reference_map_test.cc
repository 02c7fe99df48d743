#include "fusemap/io/reference_map.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <limits>

#include "fusemap/io/lcm_conversions.h"
#include "fusemap/io/lcm_log.h"
#include "fusemap/mapping/grid_image.h"

namespace fusemap {
namespace io {
namespace {

using mapping::kUnknownPixel;

constexpr double kPi = 3.14159265358979323846;
constexpr double kHalfSideM = 3.0;  // a square room centred on the map origin

// A 360-beam scan of the room from `T_map_laser`.
sensor::LaserScan RoomScan(const common::Rigid2d& T_map_laser, double stamp_s) {
  sensor::LaserScan scan;
  scan.stamp_s = stamp_s;
  scan.angle_min_rad = static_cast<float>(-kPi);
  scan.angle_increment_rad = static_cast<float>(2.0 * kPi / 360);
  scan.range_max_m = 20.f;
  for (int i = 0; i < 360; ++i) {
    const double angle = T_map_laser.angle_rad() + scan.angle_min_rad + i * scan.angle_increment_rad;
    const Eigen::Vector2d d(std::cos(angle), std::sin(angle));
    const Eigen::Vector2d o = T_map_laser.translation();
    double range = std::numeric_limits<double>::infinity();
    for (int axis = 0; axis < 2; ++axis) {
      if (std::abs(d[axis]) < 1e-12) continue;
      const double wall = d[axis] > 0 ? kHalfSideM : -kHalfSideM;
      range = std::min(range, (wall - o[axis]) / d[axis]);
    }
    scan.ranges_m.push_back(static_cast<float>(range));
  }
  return scan;
}

// The pixel of a map-frame point; kUnknownPixel outside the image.
uint8_t PixelAt(const MapImage& map, const Eigen::Vector2d& p) {
  const int col = static_cast<int>(std::floor((p.x() - map.origin_m.x()) / map.resolution_m));
  const int row =
      map.height - 1 - static_cast<int>(std::floor((p.y() - map.origin_m.y()) / map.resolution_m));
  if (col < 0 || row < 0 || col >= map.width || row >= map.height) return kUnknownPixel;
  return map.pixels[static_cast<size_t>(row) * map.width + col];
}

// The darkest pixel within a cell of `p`: a hit on a cell border may fall on either side.
uint8_t DarkestNear(const MapImage& map, const Eigen::Vector2d& p) {
  uint8_t darkest = 255;
  for (double dx : {-1.0, 0.0, 1.0}) {
    for (double dy : {-1.0, 0.0, 1.0}) {
      darkest = std::min(darkest, PixelAt(map, p + map.resolution_m * Eigen::Vector2d(dx, dy)));
    }
  }
  return darkest;
}

// Pixels are 255 * (1 - p) between the free and occupied thresholds: darker than this is more
// likely occupied than not.
constexpr uint8_t kEvenOdds = 128;

class ReferenceMapTest : public ::testing::Test {
 protected:
  void SetUp() override {
    log_path_ = testing::TempDir() + "/fusemap_reference_map_" + std::to_string(getpid()) + ".lcm";
    LcmLogWriter writer;
    std::string error;
    ASSERT_TRUE(writer.Open(log_path_, &error)) << error;
    // Scans at known poses; the poses for the stamps 0.1 .. 1.2 (not the last scan's).
    for (int i = 0; i < 13; ++i) {
      const double stamp_s = 0.1 * (i + 1);
      const common::Rigid2d T_map_laser(-1.0 + 0.15 * i, 0.5 - 0.05 * i, 0.3 * i);
      const auto bytes = EncodeLaserScan(RoomScan(T_map_laser, stamp_s));
      ASSERT_TRUE(writer.Write("LIDAR", StampToUtime(stamp_s), bytes.data(),
                               static_cast<int>(bytes.size())));
      if (i < 12) {
        poses_.push_back({stamp_s, common::Rigid3d::FromRigid2d(T_map_laser)});
      }
    }
    writer.Close();
    config_.map_builder.local_slam.submaps.num_range_data = 5;  // three grids
    config_.map_builder.local_slam.range_gate.max_range_m = 10.f;
  }
  void TearDown() override { std::remove(log_path_.c_str()); }

  std::string log_path_;
  eval::Trajectory poses_;
  SlamConfig config_;
};

TEST_F(ReferenceMapTest, DrawsTheScansAtTheirPoses) {
  ReferenceMap out;
  std::string error;
  ASSERT_TRUE(RenderLogAtPoses(log_path_, config_, poses_, common::Rigid2d::Identity(), &out,
                               &error))
      << error;
  EXPECT_EQ(out.scans_read, 13);
  EXPECT_EQ(out.scans_used, 12);
  ASSERT_EQ(out.trajectory_xy.size(), 12u);
  EXPECT_NEAR(out.trajectory_xy[0].x(), -1.0, 1e-9);
  EXPECT_NEAR(out.map.resolution_m, 0.05, 1e-12);
  // Walls more likely occupied than not, the room's inside known and more likely free.
  EXPECT_LT(DarkestNear(out.map, {kHalfSideM, 0.5}), kEvenOdds);
  EXPECT_LT(DarkestNear(out.map, {0.5, -kHalfSideM}), kEvenOdds);
  EXPECT_GT(PixelAt(out.map, {0.0, 0.0}), kEvenOdds);
  EXPECT_NE(PixelAt(out.map, {0.0, 0.0}), kUnknownPixel);
}

TEST_F(ReferenceMapTest, MovesTheDrawingOntoTheAnchor) {
  // Our trajectory starts elsewhere: the reference is drawn from there.
  const common::Rigid2d T_ours_first(10.0, 20.0, kPi / 2);
  eval::Trajectory ours = {{0.1, common::Rigid3d::FromRigid2d(T_ours_first)}};
  common::Rigid2d T_ours_map;
  ASSERT_TRUE(AnchorOnFirstPose(poses_, ours, &T_ours_map));
  const common::Rigid2d first = T_ours_map * common::Rigid2d(-1.0, 0.5, 0.0);
  EXPECT_NEAR((first.translation() - T_ours_first.translation()).norm(), 0.0, 1e-9);
  EXPECT_NEAR(std::remainder(first.angle_rad() - kPi / 2, 2 * kPi), 0.0, 1e-9);

  ReferenceMap out;
  std::string error;
  ASSERT_TRUE(RenderLogAtPoses(log_path_, config_, poses_, T_ours_map, &out, &error)) << error;
  // The wall x = +3 of the reference frame, seen from our frame.
  const Eigen::Vector2d wall = T_ours_map * Eigen::Vector2d(kHalfSideM, 0.5);
  EXPECT_LT(DarkestNear(out.map, wall), kEvenOdds);

  ours[0].stamp_s = 5.0;  // no reference pose there
  EXPECT_FALSE(AnchorOnFirstPose(poses_, ours, &T_ours_map));
}

TEST_F(ReferenceMapTest, NoPoseForAnyScanIsAnError) {
  eval::Trajectory elsewhere = {{100.0, common::Rigid3d()}};
  ReferenceMap out;
  std::string error;
  EXPECT_FALSE(RenderLogAtPoses(log_path_, config_, elsewhere, common::Rigid2d::Identity(), &out,
                                &error));
  EXPECT_NE(error.find(log_path_), std::string::npos) << error;
  EXPECT_FALSE(RenderLogAtPoses("/nonexistent.lcm", config_, poses_, common::Rigid2d::Identity(),
                                &out, &error));
}

}  // namespace
}  // namespace io
}  // namespace fusemap
