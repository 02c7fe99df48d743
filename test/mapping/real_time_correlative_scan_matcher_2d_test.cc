#include "fusemap/mapping/scan_matching/real_time_correlative_scan_matcher_2d.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace fusemap {
namespace mapping {
namespace {

struct Segment {
  Eigen::Vector2d a;
  Eigen::Vector2d b;
};

// A 7.95 m x 5.95 m room with a 1 m pillar; wall lines pass through cell centres.
std::vector<Segment> RoomWalls() {
  const auto box = [](double x0, double y0, double x1, double y1) {
    return std::vector<Segment>{{{x0, y0}, {x1, y0}}, {{x1, y0}, {x1, y1}},
                                {{x1, y1}, {x0, y1}}, {{x0, y1}, {x0, y0}}};
  };
  std::vector<Segment> walls = box(-3.975, -2.975, 3.975, 2.975);
  const std::vector<Segment> pillar = box(1.025, 0.525, 2.025, 1.525);
  walls.insert(walls.end(), pillar.begin(), pillar.end());
  return walls;
}

double DistanceToSegment(const Eigen::Vector2d& p, const Segment& s) {
  const Eigen::Vector2d ab = s.b - s.a;
  const double t = std::clamp((p - s.a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (s.a + t * ab - p).norm();
}

// Walls drawn with a Gaussian profile (sigma one cell), as many insertions would leave them.
ProbabilityGrid MakeRoomGrid() {
  MapLimits limits;
  limits.resolution_m = 0.05;
  limits.origin_m = Eigen::Vector2d(-5.0, -4.0);
  limits.num_x_cells = 200;
  limits.num_y_cells = 160;
  ProbabilityGrid grid(limits);
  const std::vector<Segment> walls = RoomWalls();
  for (int y = 0; y < limits.num_y_cells; ++y) {
    for (int x = 0; x < limits.num_x_cells; ++x) {
      const Eigen::Array2i cell(x, y);
      double d = std::numeric_limits<double>::max();
      for (const Segment& s : walls) d = std::min(d, DistanceToSegment(limits.GetCellCenter(cell), s));
      grid.SetProbability(cell, static_cast<float>(0.1 + 0.8 * std::exp(-d * d / (2 * 0.05 * 0.05))));
    }
  }
  return grid;
}

// Ray-cast returns (in the tracking frame) of `num_beams` beams from T_grid_tracking.
sensor::PointCloud2d CastScan(const common::Rigid2d& T_grid_tracking, int num_beams) {
  const std::vector<Segment> walls = RoomWalls();
  sensor::PointCloud2d cloud;
  for (int i = 0; i < num_beams; ++i) {
    const double beam_rad = 2.0 * common::kPi * i / num_beams;
    const Eigen::Vector2d dir = T_grid_tracking.rotation() * Eigen::Vector2d(std::cos(beam_rad), std::sin(beam_rad));
    const Eigen::Vector2d o = T_grid_tracking.translation();
    double best_range_m = 10.0;
    for (const Segment& s : walls) {
      const Eigen::Vector2d e = s.b - s.a;
      const double denom = dir.x() * e.y() - dir.y() * e.x();
      if (std::abs(denom) < 1e-12) continue;
      const Eigen::Vector2d w = s.a - o;
      const double range_m = (w.x() * e.y() - w.y() * e.x()) / denom;
      const double u = (w.x() * dir.y() - w.y() * dir.x()) / denom;
      if (range_m > 0.0 && u >= 0.0 && u <= 1.0) best_range_m = std::min(best_range_m, range_m);
    }
    if (best_range_m < 10.0) {
      cloud.push_back((best_range_m * Eigen::Vector2d(std::cos(beam_rad), std::sin(beam_rad))).cast<float>());
    }
  }
  return cloud;
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
  auto reader = common::ConfigReader::FromString("{linear_search_window_m: 0.2, angular_search_window_rad: 0.35, translation_delta_cost_weight: 0.2, rotation_delta_cost_weight: 0.3}", "test", &error);
  ASSERT_NE(reader, nullptr) << error;
  const auto options = ParseRealTimeCorrelativeScanMatcherOptions2D(*reader);
  EXPECT_TRUE(reader->Finish(&error)) << error;
  EXPECT_EQ(options.linear_search_window_m, 0.2);
  EXPECT_EQ(options.angular_search_window_rad, 0.35);
  EXPECT_EQ(options.translation_delta_cost_weight, 0.2);
  EXPECT_EQ(options.rotation_delta_cost_weight, 0.3);
  auto bad = common::ConfigReader::FromString("{linear_search_window_m: -1.0}", "bad.yaml", &error);
  ASSERT_NE(bad, nullptr) << error;
  ParseRealTimeCorrelativeScanMatcherOptions2D(*bad);
  EXPECT_FALSE(bad->Finish(&error));
  EXPECT_NE(error.find("bad.yaml"), std::string::npos) << error;
}

}  // namespace
}  // namespace mapping
}  // namespace fusemap
