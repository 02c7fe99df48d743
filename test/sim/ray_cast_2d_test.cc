#include "fusemap/sim/ray_cast_2d.h"

#include <gtest/gtest.h>

#include <cmath>

#include "fusemap/sim/laser_simulator.h"

namespace fusemap {
namespace sim {
namespace {

Prism Wall(double cx, double cy, double half_x, double half_y, double yaw_rad, double height_m = 3.0) {
  Prism p;
  p.centre_m = Eigen::Vector2d(cx, cy);
  p.half_size_m = Eigen::Vector2d(half_x, half_y);
  p.yaw_rad = yaw_rad;
  p.z_max_m = height_m;
  return p;
}

TEST(RayCast2dTest, AxisAlignedWallGivesDistanceToNearFace) {
  // Wall 0.2 m thick centred on x = 5: near face at x = 4.9.
  const std::vector<Prism> prisms = {Wall(5.0, 0.0, 0.1, 2.0, 0.0)};
  int hit = -1;
  EXPECT_NEAR(CastRay2d(prisms, Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0), 0.3, 12.0, &hit), 4.9, 1e-12);
  EXPECT_EQ(hit, 0);
  // 20 deg off axis (hits at y = 1.78, within the wall): 4.9 / cos(20 deg).
  const double a = M_PI / 9;
  EXPECT_NEAR(CastRay2d(prisms, Eigen::Vector2d(0, 0), Eigen::Vector2d(std::cos(a), std::sin(a)), 0.3,
                        12.0, &hit),
              4.9 / std::cos(a), 1e-12);
  // Past the wall's end (y = 2) nothing is hit: max range, no index.
  EXPECT_DOUBLE_EQ(CastRay2d(prisms, Eigen::Vector2d(0, 2.5), Eigen::Vector2d(1, 0), 0.3, 12.0, &hit), 12.0);
  EXPECT_EQ(hit, -1);
}

TEST(RayCast2dTest, RotatedWallAndCircle) {
  // A wall through (4, 0) rotated 45 deg (its long axis along the diagonal); its near face
  // along the x axis is hit where the face line crosses y = 0: x = 4 - 0.1 * sqrt(2).
  const std::vector<Prism> rotated = {Wall(4.0, 0.0, 3.0, 0.1, M_PI / 4)};
  int hit = -1;
  EXPECT_NEAR(CastRay2d(rotated, Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0), 0.3, 12.0, &hit),
              4.0 - 0.1 * std::sqrt(2.0), 1e-9);
  Prism pillar;
  pillar.shape = Prism::Shape::kCircle;
  pillar.centre_m = Eigen::Vector2d(0.0, 3.0);
  pillar.radius_m = 0.5;
  pillar.z_max_m = 3.0;
  EXPECT_NEAR(CastRay2d({pillar}, Eigen::Vector2d(0, 0), Eigen::Vector2d(0, 1), 0.3, 12.0, &hit), 2.5, 1e-12);
}

TEST(RayCast2dTest, ScanHeightFiltersLowObjects) {
  // A 0.2 m high box in front of a wall: invisible to a scanner at 0.3 m, seen at 0.1 m.
  const std::vector<Prism> prisms = {Wall(2.0, 0.0, 0.25, 0.25, 0.0, 0.2), Wall(6.0, 0.0, 0.1, 3.0, 0.0)};
  int hit = -1;
  EXPECT_NEAR(CastRay2d(prisms, Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0), 0.3, 12.0, &hit), 5.9, 1e-12);
  EXPECT_EQ(hit, 1);
  EXPECT_NEAR(CastRay2d(prisms, Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0), 0.1, 12.0, &hit), 1.75, 1e-12);
  EXPECT_EQ(hit, 0);
}

TEST(LaserSimulatorTest, NoiselessScanOfKnownWall) {
  LaserOptions options;
  options.range_noise_stddev_m = 0.0;
  // Robot at (1, 0) facing +y; wall along y = 5 (near face y = 4.9): the middle beam (angle 0)
  // reads 4.9 m; beams looking backwards see nothing.
  const std::vector<Prism> prisms = {Wall(0.0, 5.0, 20.0, 0.1, 0.0)};
  std::mt19937_64 rng(1);
  const sensor::LaserScan scan =
      SimulateLaserScan(prisms, common::Rigid2d(1.0, 0.0, M_PI / 2), 3.0, options, &rng);
  ASSERT_EQ(scan.ranges_m.size(), 811u);
  EXPECT_NEAR(scan.angle_min_rad, -0.75 * M_PI, 1e-6);
  EXPECT_NEAR(scan.angle_increment_rad, 1.5 * M_PI / 810, 1e-7);
  EXPECT_NEAR(scan.ranges_m[405], 4.9, 1e-5);
  const double angle_100 = scan.angle_min_rad + 100 * scan.angle_increment_rad;  // -1.97 rad
  EXPECT_NEAR(scan.ranges_m[300], 4.9 / std::cos(scan.angle_min_rad + 300 * scan.angle_increment_rad), 1e-4);
  EXPECT_LT(std::cos(angle_100), 0.0);
  EXPECT_FLOAT_EQ(scan.ranges_m[100], 12.0f);  // Looking away from the wall: no return.
  EXPECT_DOUBLE_EQ(scan.stamp_s, 3.0);
}

}  // namespace
}  // namespace sim
}  // namespace fusemap
