#include "fusemap/sim/surface_distance.h"

#include <gtest/gtest.h>

#include <cmath>

#include "fusemap/common/math.h"

namespace fusemap {
namespace sim {
namespace {

constexpr double kTol = 1e-9;

// A 3 m high room with one box rotated by 90 degrees (so its long side runs along y) and one
// pillar, plus one person walking an L-shaped path.
World TinyWorld() {
  World world;
  world.ceiling_height_m = 3.0;
  Prism box;
  box.shape = Prism::Shape::kRectangle;
  box.centre_m = Eigen::Vector2d(5.0, 0.0);
  box.half_size_m = Eigen::Vector2d(2.0, 0.5);  // 4 m x 1 m, turned: 1 m in x, 4 m in y.
  box.yaw_rad = common::kPi / 2;
  box.z_min_m = 0.0;
  box.z_max_m = 1.0;
  Prism pillar;
  pillar.shape = Prism::Shape::kCircle;
  pillar.centre_m = Eigen::Vector2d(-5.0, 0.0);
  pillar.radius_m = 0.3;
  pillar.z_min_m = 0.0;
  pillar.z_max_m = 3.0;
  world.prisms = {box, pillar};
  Person person;
  person.path_m = {Eigen::Vector2d(0.0, 5.0), Eigen::Vector2d(4.0, 5.0), Eigen::Vector2d(4.0, 9.0)};
  person.radius_m = 0.25;
  person.height_m = 1.8;
  world.people = {person};
  return world;
}

TEST(SurfaceDistanceTest, FloorAndCeiling) {
  const World world = TinyWorld();
  EXPECT_NEAR(DistanceToStaticSurface(world, Eigen::Vector3d(0.0, -3.0, 0.0)), 0.0, kTol);
  EXPECT_NEAR(DistanceToStaticSurface(world, Eigen::Vector3d(0.0, -3.0, 0.4)), 0.4, kTol);
  EXPECT_NEAR(DistanceToStaticSurface(world, Eigen::Vector3d(0.0, -3.0, 2.9)), 0.1, kTol);
  EXPECT_NEAR(DistanceToStaticSurface(world, Eigen::Vector3d(0.0, -3.0, -0.02)), 0.02, kTol);
}

TEST(SurfaceDistanceTest, RotatedBoxSidesTopAndInside) {
  const World world = TinyWorld();
  // Turned box spans x in [4.5, 5.5], y in [-2, 2], z in [0, 1].
  EXPECT_NEAR(DistanceToStaticSurface(world, Eigen::Vector3d(5.7, 1.5, 0.5)), 0.2, kTol);
  EXPECT_NEAR(DistanceToStaticSurface(world, Eigen::Vector3d(5.0, 2.05, 0.5)), 0.05, kTol);
  EXPECT_NEAR(DistanceToStaticSurface(world, Eigen::Vector3d(5.0, 0.0, 1.5)), 1.5 - 1.0, kTol);
  // Inside, nearest face is +x at 0.1 m (top is 0.5 m, floor 0.5 m).
  EXPECT_NEAR(DistanceToStaticSurface(world, Eigen::Vector3d(5.4, 0.0, 0.5)), 0.1, kTol);
  // Diagonally off the top edge: sqrt(0.3^2 + 0.4^2).
  EXPECT_NEAR(DistanceToStaticSurface(world, Eigen::Vector3d(5.0, 2.3, 1.4)), 0.5, kTol);
  // Unturned, the box would reach x = 7 and this point would sit 0.5 m above its top.
  EXPECT_NEAR(DistanceToStaticSurface(world, Eigen::Vector3d(6.5, 0.0, 1.5)), std::hypot(1.0, 0.5),
              kTol);
}

TEST(SurfaceDistanceTest, PillarSideAndInside) {
  const World world = TinyWorld();
  EXPECT_NEAR(DistanceToStaticSurface(world, Eigen::Vector3d(-5.0, 0.8, 1.5)), 0.5, kTol);
  EXPECT_NEAR(DistanceToStaticSurface(world, Eigen::Vector3d(-4.9, 0.0, 1.5)), 0.2, kTol);
}

TEST(SurfaceDistanceTest, PeoplePathVolume) {
  const World world = TinyWorld();
  // On the path's first leg, inside the swept volume.
  EXPECT_NEAR(DistanceToPeoplePaths(world, Eigen::Vector3d(2.0, 5.1, 1.0)), 0.0, kTol);
  // Beside the first leg: 0.75 m from the polyline, minus the radius.
  EXPECT_NEAR(DistanceToPeoplePaths(world, Eigen::Vector3d(2.0, 4.25, 1.0)), 0.5, kTol);
  // Past the corner's outside, 1 m from the vertex (4, 5) diagonally.
  const double d = 1.0 / std::sqrt(2.0);
  EXPECT_NEAR(DistanceToPeoplePaths(world, Eigen::Vector3d(4.0 + d, 5.0 - d, 1.0)), 0.75, kTol);
  // Above the head.
  EXPECT_NEAR(DistanceToPeoplePaths(world, Eigen::Vector3d(4.0, 8.0, 2.1)), 0.3, kTol);
  // Beyond the path's end: 1 m past (4, 9) and 0.3 m above the head.
  EXPECT_NEAR(DistanceToPeoplePaths(world, Eigen::Vector3d(4.0, 10.0, 2.1)), std::hypot(0.75, 0.3), kTol);
  World empty;
  EXPECT_TRUE(std::isinf(DistanceToPeoplePaths(empty, Eigen::Vector3d(0.0, 0.0, 1.0))));
}

}  // namespace
}  // namespace sim
}  // namespace fusemap
