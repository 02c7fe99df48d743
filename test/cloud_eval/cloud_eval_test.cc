#include "fusemap/cloud_eval/cloud_eval.h"

#include <gtest/gtest.h>

#include <cmath>

#include "testing/tiny_world.h"

namespace fusemap {
namespace cloud_eval {
namespace {

using test_world::Point;
using test_world::TinyWorld;

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

}  // namespace
}  // namespace cloud_eval
}  // namespace fusemap
