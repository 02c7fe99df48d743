#include "fusemap/mapping/scan_matching/correlative_scan_matcher_2d.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fusemap {
namespace mapping {
namespace {

TEST(CorrelativeScanMatcher2DTest, AngularStepMovesFarthestPointAtMostOneCell) {
  for (double range_m : {0.3, 1.0, 5.0, 30.0}) {
    const double step_rad = ComputeAngularStep(range_m, 0.05);
    const double chord_m = 2.0 * range_m * std::sin(step_rad / 2.0);
    EXPECT_LE(chord_m, 0.05);
    EXPECT_GT(chord_m, 0.049);
  }
}

TEST(CorrelativeScanMatcher2DTest, SearchParametersCoverTheWindows) {
  const sensor::PointCloud2d cloud = {Eigen::Vector2f(4.f, 3.f), Eigen::Vector2f(-1.f, 0.f)};
  const SearchParameters params(0.12, 0.1, cloud, 0.05);
  EXPECT_NEAR(params.angular_step_rad, ComputeAngularStep(5.0, 0.05), 1e-6);
  EXPECT_GE(params.num_angular_perturbations * params.angular_step_rad, 0.1);
  EXPECT_LT((params.num_angular_perturbations - 1) * params.angular_step_rad, 0.1);
  EXPECT_EQ(params.num_scans, 2 * params.num_angular_perturbations + 1);
  ASSERT_EQ(static_cast<int>(params.linear_bounds.size()), params.num_scans);
  EXPECT_EQ(params.linear_bounds[0].min_x, -3);
  EXPECT_EQ(params.linear_bounds[0].max_y, 3);
}

TEST(CorrelativeScanMatcher2DTest, RotatedScansAndCandidatesAgree) {
  const sensor::PointCloud2d cloud = {Eigen::Vector2f(1.f, 0.f)};
  const SearchParameters params(2, 3, 0.25, 0.1);
  const std::vector<sensor::PointCloud2d> scans = GenerateRotatedScans(cloud, params);
  ASSERT_EQ(scans.size(), 7u);
  for (int i = 0; i < 7; ++i) {
    const Candidate2D candidate(i, 1, -2, params);
    EXPECT_NEAR(candidate.angle_rad, (i - 3) * 0.25, 1e-12);
    EXPECT_NEAR(candidate.x_m, 0.1, 1e-12);
    EXPECT_NEAR(candidate.y_m, -0.2, 1e-12);
    EXPECT_NEAR(scans[i][0].x(), std::cos(candidate.angle_rad), 1e-6);
    EXPECT_NEAR(scans[i][0].y(), std::sin(candidate.angle_rad), 1e-6);
  }
}

TEST(CorrelativeScanMatcher2DTest, DiscretizeAndShrinkToFit) {
  MapLimits limits;
  limits.resolution_m = 0.1;
  limits.origin_m = Eigen::Vector2d(-1.0, -1.0);
  limits.num_x_cells = 20;
  limits.num_y_cells = 20;
  const std::vector<sensor::PointCloud2d> scans = {{Eigen::Vector2f(0.05f, 0.05f), Eigen::Vector2f(0.35f, -0.25f)}};
  const std::vector<DiscreteScan2D> discrete = DiscretizeScans(limits, scans, Eigen::Vector2f(0.5f, 0.f));
  ASSERT_EQ(discrete.size(), 1u);
  EXPECT_EQ(discrete[0][0].x(), 15);
  EXPECT_EQ(discrete[0][0].y(), 10);
  EXPECT_EQ(discrete[0][1].x(), 18);
  EXPECT_EQ(discrete[0][1].y(), 7);
  SearchParameters params(30, 0, 0.1, 0.1);
  params.ShrinkToFit(discrete, limits);
  // Offsets keep the scan's bounding box (x 15..18, y 7..10) overlapping the grid.
  EXPECT_EQ(params.linear_bounds[0].min_x, -18);
  EXPECT_EQ(params.linear_bounds[0].max_x, 4);
  EXPECT_EQ(params.linear_bounds[0].min_y, -10);
  EXPECT_EQ(params.linear_bounds[0].max_y, 12);
}

}  // namespace
}  // namespace mapping
}  // namespace fusemap
