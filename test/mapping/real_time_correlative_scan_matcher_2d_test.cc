#include "fusemap/mapping/scan_matching/real_time_correlative_scan_matcher_2d.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "testing/wall_grid.h"

namespace fusemap {
namespace mapping {
namespace {

using test_world::Segment;

ProbabilityGrid MakeRoomGrid() { return test_world::MakeSmallRoomGrid(); }

// Ray-cast returns (in the tracking frame) of `num_beams` beams from T_grid_tracking.
sensor::PointCloud2d CastScan(const common::Rigid2d& T_grid_tracking, int num_beams) {
  return test_world::CastCloud(test_world::SmallRoomWalls(), T_grid_tracking, num_beams, 10.0);
}

TEST(RealTimeCorrelativeScanMatcher2DTest, RecoversOffsetToWithinOneStep) {
  const ProbabilityGrid grid = MakeRoomGrid();
  const common::Rigid2d truth(-1.0, -0.5, 0.3);
  const sensor::PointCloud2d cloud = CastScan(truth, 180);
  ASSERT_EQ(cloud.size(), 180u);
  const common::Rigid2d start(truth.x() + 0.12, truth.y() + 0.16, truth.angle_rad() + common::DegToRad(5.0));

  RealTimeCorrelativeScanMatcherOptions2D options;
  options.linear_search_window_m = 0.3;  // the default 0.1 m cannot reach a 0.2 m error
  RealTimeCorrelativeScanMatcher2D matcher(options);
  common::Rigid2d pose;
  const double score = matcher.Match(start, cloud, grid, &pose);

  // The candidate lattice is offset from the truth by the start's sub-cell error, so the best
  // candidate is within half a cell per axis and half an angular step.
  EXPECT_LT(std::abs(pose.x() - truth.x()), 0.026);
  EXPECT_LT(std::abs(pose.y() - truth.y()), 0.026);
  EXPECT_LT(std::abs(common::NormalizeAngle(pose.angle_rad() - truth.angle_rad())), common::DegToRad(0.5));
  EXPECT_GT(score, 0.6);
}

TEST(RealTimeCorrelativeScanMatcher2DTest, ExactStartStaysPut) {
  const ProbabilityGrid grid = MakeRoomGrid();
  const common::Rigid2d truth(0.5, -1.0, -2.0);
  RealTimeCorrelativeScanMatcher2D matcher(RealTimeCorrelativeScanMatcherOptions2D{});
  common::Rigid2d pose;
  matcher.Match(truth, CastScan(truth, 90), grid, &pose);
  EXPECT_NEAR(pose.x(), truth.x(), 1e-9);
  EXPECT_NEAR(pose.y(), truth.y(), 1e-9);
  EXPECT_NEAR(pose.angle_rad(), truth.angle_rad(), 1e-9);
}

// The flag that lets local SLAM widen its search: set when the prediction is further off than
// the window, clear when the optimum lies inside it.
TEST(RealTimeCorrelativeScanMatcher2DTest, ReportsBestCandidateOnWindowEdge) {
  const ProbabilityGrid grid = MakeRoomGrid();
  const common::Rigid2d truth(-1.0, -0.5, 0.3);
  const sensor::PointCloud2d cloud = CastScan(truth, 180);
  RealTimeCorrelativeScanMatcherOptions2D options;
  options.linear_search_window_m = 0.3;
  options.angular_search_window_rad = common::DegToRad(10.0);
  RealTimeCorrelativeScanMatcher2D matcher(options);
  common::Rigid2d pose;
  bool at_edge = true;
  matcher.Match(common::Rigid2d(truth.x() + 0.1, truth.y(), truth.angle_rad() + 0.05), cloud, grid,
                &pose, &at_edge);
  EXPECT_FALSE(at_edge);
  // 25 deg off: the best the window holds is its outermost angle.
  matcher.Match(common::Rigid2d(truth.x(), truth.y(), truth.angle_rad() + common::DegToRad(25.0)),
                cloud, grid, &pose, &at_edge);
  EXPECT_TRUE(at_edge);
  // 0.4 m off along x: its outermost offset.
  matcher.Match(common::Rigid2d(truth.x() + 0.4, truth.y(), truth.angle_rad()), cloud, grid, &pose,
                &at_edge);
  EXPECT_TRUE(at_edge) << pose.x() - truth.x() << " " << pose.y() - truth.y();
}

// A robot entering new space: the mapped part (x < 0) is observed free (p = 0.4) with a long
// wall at y = 1 m; the wall ahead, at x = 0.5 m, was never seen. Its points, in unknown cells,
// must not be dragged back into the observed free space.
TEST(RealTimeCorrelativeScanMatcher2DTest, NewSpaceCountsAsNoEvidence) {
  MapLimits limits;
  limits.resolution_m = 0.05;
  limits.origin_m = Eigen::Vector2d(-3.0, -2.0);
  limits.num_x_cells = 120;
  limits.num_y_cells = 80;
  ProbabilityGrid grid(limits);
  for (int x = 0; x < limits.num_x_cells; ++x) {
    for (int y = 0; y < limits.num_y_cells; ++y) {
      const Eigen::Vector2d centre = limits.GetCellCenter(Eigen::Array2i(x, y));
      if (std::abs(centre.y() - 1.0) < 0.03) {
        grid.SetProbability(Eigen::Array2i(x, y), 0.9f);
      } else if (centre.x() < 0.0 && centre.y() < 1.0) {
        grid.SetProbability(Eigen::Array2i(x, y), 0.4f);
      }
    }
  }
  sensor::PointCloud2d cloud;
  for (int i = 0; i < 40; ++i) cloud.emplace_back(-2.0f + 0.1f * i, 1.0f);  // the mapped wall
  for (int i = 0; i < 40; ++i) cloud.emplace_back(0.5f, -1.5f + 0.06f * i);  // the new wall
  RealTimeCorrelativeScanMatcherOptions2D options;
  options.linear_search_window_m = 0.6;
  common::Rigid2d pose;
  RealTimeCorrelativeScanMatcher2D(options).Match(common::Rigid2d::Identity(), cloud, grid, &pose);
  EXPECT_NEAR(pose.x(), 0.0, 0.026);
  EXPECT_NEAR(pose.y(), 0.0, 0.026);
  // Reading never-observed cells as the grid stores them (kMinProbability, below the free
  // space's 0.4) pulls the new wall back into the mapped area by the whole window.
  options.unknown_probability = kMinProbability;
  RealTimeCorrelativeScanMatcher2D(options).Match(common::Rigid2d::Identity(), cloud, grid, &pose);
  EXPECT_LT(pose.x(), -0.5);
}

// Cells off the grid read as unknown: a scan reaching past the grid's edge (the matcher's
// checked path) scores as it does on a larger grid where those cells are unknown (its
// unchecked path), so the two give the same match.
TEST(RealTimeCorrelativeScanMatcher2DTest, CellsOffTheGridScoreAsUnknownCells) {
  const ProbabilityGrid large = test_world::DrawWalls(MakeRoomGrid().limits(),
                                                      test_world::SmallRoomWalls(), 0.2);
  const ProbabilityGrid cropped = large.Cropped();
  ASSERT_LT(cropped.limits().num_x_cells, large.limits().num_x_cells);
  const common::Rigid2d truth(-1.0, -0.5, 0.3);
  sensor::PointCloud2d cloud = CastScan(truth, 180);
  // Through an open door: returns 0.5 m beyond the east wall, off the cropped grid.
  for (int i = 0; i < 20; ++i) {
    cloud.push_back((truth.inverse() * Eigen::Vector2d(4.5, -1.0 + 0.1 * i)).cast<float>());
  }
  RealTimeCorrelativeScanMatcherOptions2D options;
  options.unknown_probability = 0.3;
  const RealTimeCorrelativeScanMatcher2D matcher(options);
  const common::Rigid2d start(truth.x() + 0.04, truth.y() - 0.03, truth.angle_rad() + 0.02);
  common::Rigid2d on_large;
  common::Rigid2d on_cropped;
  const double large_score = matcher.Match(start, cloud, large, &on_large);
  const double cropped_score = matcher.Match(start, cloud, cropped, &on_cropped);
  EXPECT_DOUBLE_EQ(cropped_score, large_score);
  EXPECT_DOUBLE_EQ(on_cropped.x(), on_large.x());
  EXPECT_DOUBLE_EQ(on_cropped.y(), on_large.y());
  EXPECT_DOUBLE_EQ(on_cropped.angle_rad(), on_large.angle_rad());
  EXPECT_NEAR(on_large.x(), truth.x(), 0.026);
  EXPECT_NEAR(on_large.y(), truth.y(), 0.026);
}

TEST(RealTimeCorrelativeScanMatcher2DTest, EmptyCloudReturnsInitialPose) {
  const ProbabilityGrid grid = MakeRoomGrid();
  RealTimeCorrelativeScanMatcher2D matcher(RealTimeCorrelativeScanMatcherOptions2D{});
  common::Rigid2d pose;
  EXPECT_EQ(matcher.Match(common::Rigid2d(1.0, 2.0, 0.5), {}, grid, &pose), 0.0);
  EXPECT_EQ(pose.x(), 1.0);
  EXPECT_EQ(pose.angle_rad(), 0.5);
}

TEST(RealTimeCorrelativeScanMatcher2DTest, OptionsValidation) {
  std::string error;
  RealTimeCorrelativeScanMatcherOptions2D options;
  EXPECT_TRUE(options.IsValid(&error));
  options.angular_search_window_rad = -0.1;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_FALSE(error.empty());
}

TEST(RealTimeCorrelativeScanMatcher2DTest, ParsesOptionsAndRejectsOutOfRange) {
  std::string error;
  auto reader = common::ConfigReader::FromString("{linear_search_window_m: 0.2, angular_search_window_rad: 0.35, translation_delta_cost_weight: 0.2, rotation_delta_cost_weight: 0.3, unknown_probability: 0.2}", "test", &error);
  ASSERT_NE(reader, nullptr) << error;
  const auto options = ParseRealTimeCorrelativeScanMatcherOptions2D(*reader);
  EXPECT_TRUE(reader->Finish(&error)) << error;
  EXPECT_EQ(options.linear_search_window_m, 0.2);
  EXPECT_EQ(options.angular_search_window_rad, 0.35);
  EXPECT_EQ(options.translation_delta_cost_weight, 0.2);
  EXPECT_EQ(options.rotation_delta_cost_weight, 0.3);
  EXPECT_EQ(options.unknown_probability, 0.2);
  // The range's ends as written in YAML (doubles) are accepted.
  for (const char* yaml : {"{unknown_probability: 0.1}", "{unknown_probability: 0.9}"}) {
    auto ends = common::ConfigReader::FromString(yaml, "ends.yaml", &error);
    ASSERT_NE(ends, nullptr) << error;
    ParseRealTimeCorrelativeScanMatcherOptions2D(*ends);
    EXPECT_TRUE(ends->Finish(&error)) << yaml << ": " << error;
  }
  for (const char* yaml : {"{linear_search_window_m: -1.0}", "{unknown_probability: 0.95}"}) {
    auto bad = common::ConfigReader::FromString(yaml, "bad.yaml", &error);
    ASSERT_NE(bad, nullptr) << error;
    ParseRealTimeCorrelativeScanMatcherOptions2D(*bad);
    EXPECT_FALSE(bad->Finish(&error)) << yaml;
    EXPECT_NE(error.find("bad.yaml"), std::string::npos) << error;
  }
}

}  // namespace
}  // namespace mapping
}  // namespace fusemap
