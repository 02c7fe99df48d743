#include "fusemap/cloud_eval/landmark_eval.h"

#include <gtest/gtest.h>

#include <cmath>

#include "testing/tiny_world.h"

namespace fusemap {
namespace cloud_eval {
namespace {

using test_world::Point;
using test_world::TinyWorld;

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
}  // namespace cloud_eval
}  // namespace fusemap
