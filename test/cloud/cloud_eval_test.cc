#include "cloud_eval.h"

#include <gtest/gtest.h>

#include <cmath>

#include "landmark_eval.h"

namespace fusemap {
namespace cloudeval_tool {
namespace {

// A 3 m room with one wall at x = 5 (a slab x in [5, 5.2]) and a person walking along y = 2
// from x = 0 to x = 4.
sim::World TinyWorld() {
  sim::World world;
  world.ceiling_height_m = 3.0;
  sim::Prism wall;
  wall.centre_m = Eigen::Vector2d(5.1, 0.0);
  wall.half_size_m = Eigen::Vector2d(0.1, 5.0);
  wall.z_max_m = 3.0;
  world.prisms = {wall};
  sim::Person person;
  person.path_m = {Eigen::Vector2d(0.0, 2.0), Eigen::Vector2d(4.0, 2.0)};
  person.radius_m = 0.25;
  person.height_m = 1.8;
  world.people = {person};
  return world;
}

cloud::ColorPoint Point(double x, double y, double z) {
  cloud::ColorPoint p(uint8_t{100}, uint8_t{100}, uint8_t{100});
  p.x = static_cast<float>(x);
  p.y = static_cast<float>(y);
  p.z = static_cast<float>(z);
  return p;
}

TEST(CloudEvalTest, ClassifiesPointsOnPeopleAndStructure) {
  const sim::World world = TinyWorld();
  double to_static_m = 0.0;
  EXPECT_TRUE(IsDynamicPoint(world, Eigen::Vector3d(2.0, 2.1, 1.0), 0.1, &to_static_m));
  EXPECT_NEAR(to_static_m, 1.0, 1e-9);  // Floor is 1 m below; ceiling 2 m above.
  // Floor under the person's feet is static (within tolerance of the floor).
  EXPECT_FALSE(IsDynamicPoint(world, Eigen::Vector3d(2.0, 2.0, 0.05), 0.1, nullptr));
  EXPECT_FALSE(IsDynamicPoint(world, Eigen::Vector3d(4.98, 0.0, 1.5), 0.1, &to_static_m));
  EXPECT_NEAR(to_static_m, 0.02, 1e-6);
  // Clutter in mid-air far from any person counts as static (a wrong static point).
  EXPECT_FALSE(IsDynamicPoint(world, Eigen::Vector3d(2.0, -3.0, 1.5), 0.1, nullptr));
}

TEST(CloudEvalTest, FractionsAndMedian) {
  const sim::World world = TinyWorld();
  cloud::ColorCloud kept, removed;
  // Static kept: on the wall face at 0.01, 0.02, 0.03 m and floor at 0.04 m: median 0.025 m.
  kept.push_back(Point(4.99, 0.0, 1.0));
  kept.push_back(Point(4.98, 1.0, 1.0));
  kept.push_back(Point(4.97, -1.0, 1.0));
  kept.push_back(Point(1.0, -2.0, 0.04));
  kept.push_back(Point(1.0, 2.0, 1.0));  // One dynamic point left behind.
  for (int i = 0; i < 3; ++i) removed.push_back(Point(0.5 + i, 2.0, 1.2));  // Three removed.
  removed.push_back(Point(4.99, 2.0, 2.0));  // One static point wrongly removed.
  const CloudEvalResult result = EvaluateCloud(world, kept, &removed, 0.1);
  EXPECT_EQ(result.kept_static, 4);
  EXPECT_EQ(result.kept_dynamic, 1);
  EXPECT_EQ(result.removed_dynamic, 3);
  EXPECT_EQ(result.removed_static, 1);
  EXPECT_NEAR(result.median_surface_dist_m, 0.025, 1e-6);
  EXPECT_NEAR(result.dynamic_removed_frac, 0.75, 1e-12);
  EXPECT_NEAR(result.static_kept_frac, 0.8, 1e-12);
  EXPECT_EQ(FormatCloudEvalLine(result),
            "median_surface_dist_m=0.02500 dynamic_removed_frac=0.75000 static_kept_frac=0.80000");
}

TEST(CloudEvalTest, UnknownRemovedCloudGivesNaNFractions) {
  const sim::World world = TinyWorld();
  cloud::ColorCloud kept;
  kept.push_back(Point(4.95, 0.0, 1.0));
  const CloudEvalResult result = EvaluateCloud(world, kept, nullptr, 0.1);
  EXPECT_NEAR(result.median_surface_dist_m, 0.05, 1e-6);
  EXPECT_TRUE(std::isnan(result.dynamic_removed_frac));
  EXPECT_TRUE(std::isnan(result.static_kept_frac));
  EXPECT_TRUE(std::isnan(EvaluateCloud(world, cloud::ColorCloud(), nullptr, 0.1).median_surface_dist_m));
}

// A hall with a wall, two pillars 7 m apart, a low box (top 0.8 m, yawed) and a tall one.
sim::World LandmarkWorld() {
  sim::World world = TinyWorld();
  for (const double x : {1.0, 8.0}) {
    sim::Prism pillar;
    pillar.shape = sim::Prism::Shape::kCircle;
    pillar.centre_m = Eigen::Vector2d(x, 6.0);
    pillar.radius_m = 0.3;
    pillar.z_max_m = 3.0;
    world.prisms.push_back(pillar);
  }
  sim::Prism low;
  low.centre_m = Eigen::Vector2d(4.0, 9.0);
  low.half_size_m = Eigen::Vector2d(0.5, 0.3);
  low.yaw_rad = 0.3;
  low.z_max_m = 0.8;
  sim::Prism tall = low;
  tall.centre_m = Eigen::Vector2d(7.0, 9.0);
  tall.z_max_m = 1.5;
  world.prisms.push_back(low);
  world.prisms.push_back(tall);
  return world;
}

// Half of a pillar's side (the half a robot sees), moved by `offset`, heights 0.4 .. 1.9 m.
void AddPillarSide(const Eigen::Vector2d& centre, double radius, cloud::ColorCloud* cloud) {
  for (int i = 0; i <= 60; ++i) {
    const double a = M_PI * i / 60.0;
    for (double z = 0.4; z < 1.95; z += 0.1) {
      cloud->push_back(Point(centre.x() + radius * std::cos(a), centre.y() - radius * std::sin(a), z));
    }
  }
}

TEST(LandmarkEvalTest, PicksPillarsAndBoxTopsBelowTheCamera) {
  const auto landmarks = MeasurableLandmarks(LandmarkWorld(), 1.0);
  ASSERT_EQ(landmarks.size(), 3u);  // The wall and the 1.5 m box are not landmarks.
  EXPECT_EQ(landmarks[0].name, "pillar0");
  EXPECT_EQ(landmarks[1].name, "pillar1");
  EXPECT_EQ(landmarks[2].name, "box0");
  EXPECT_EQ(landmarks[2].kind, Landmark::Kind::kBoxTop);
  EXPECT_EQ(MeasurableLandmarks(LandmarkWorld(), 2.0).size(), 4u);
}

TEST(LandmarkEvalTest, CircleFitAndTopCentreRecoverShiftedLandmarks) {
  const sim::World world = LandmarkWorld();
  cloud::ColorCloud cloud;
  // Pillars mapped 2 cm east and 1 cm south of where they are: the fit must follow.
  AddPillarSide(Eigen::Vector2d(1.02, 5.99), 0.3, &cloud);
  AddPillarSide(Eigen::Vector2d(8.0, 6.0), 0.3, &cloud);
  // The low box's top, 3 cm grid, shifted 4 cm along its own x axis.
  const Eigen::Rotation2Dd R(0.3);
  for (double u = -0.5; u <= 0.5 + 1e-9; u += 0.03) {
    for (double v = -0.3; v <= 0.3 + 1e-9; v += 0.03) {
      const Eigen::Vector2d p = Eigen::Vector2d(4.0, 9.0) + R * Eigen::Vector2d(u + 0.04, v);
      cloud.push_back(Point(p.x(), p.y(), 0.81));
    }
  }
  const auto landmarks = MeasurableLandmarks(world, 1.0);
  const LandmarkEstimate pillar = EstimateLandmark(landmarks[0], cloud);
  ASSERT_TRUE(pillar.found);
  EXPECT_NEAR(pillar.xy_m.x(), 1.02, 1e-4);
  EXPECT_NEAR(pillar.xy_m.y(), 5.99, 1e-4);
  const LandmarkEstimate top = EstimateLandmark(landmarks[2], cloud);
  ASSERT_TRUE(top.found);
  const Eigen::Vector2d expected = Eigen::Vector2d(4.0, 9.0) + R * Eigen::Vector2d(0.04, 0.0);
  EXPECT_NEAR((top.xy_m - expected).norm(), 0.0, 0.02);  // Footprint margin clips 1 cm of shift.

  const auto pairs = EvaluateLandmarkPairs(world, cloud, 1.0);
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_NEAR(pairs[0].true_m, 7.0, 1e-12);
  EXPECT_NEAR(pairs[0].measured_m, std::hypot(6.98, 0.01), 1e-4);
  EXPECT_NEAR(pairs[0].rel_err, std::abs(std::hypot(6.98, 0.01) - 7.0) / 7.0, 2e-5);
  EXPECT_EQ(FormatLandmarkSummary(pairs).substr(0, 26), "landmark_pair_max_rel_err=");
  EXPECT_NE(FormatLandmarkSummary(pairs).find("landmark_pairs_found=2/2"), std::string::npos);
}

TEST(LandmarkEvalTest, TooFewPointsIsNotFound) {
  const sim::World world = LandmarkWorld();
  cloud::ColorCloud cloud;
  AddPillarSide(Eigen::Vector2d(1.0, 6.0), 0.3, &cloud);
  const auto pairs = EvaluateLandmarkPairs(world, cloud, 1.0);
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_TRUE(std::isnan(pairs[0].rel_err));
  EXPECT_NE(FormatLandmarkSummary(pairs).find("landmark_pairs_found=0/2"), std::string::npos);
}

}  // namespace
}  // namespace cloudeval_tool
}  // namespace fusemap
