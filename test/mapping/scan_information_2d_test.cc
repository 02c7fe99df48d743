#include "fusemap/mapping/scan_matching/scan_information_2d.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "fusemap/sensor/voxel_filter.h"
#include "testing/wall_grid.h"

namespace fusemap {
namespace mapping {
namespace {

using test_world::Segment;

// A 2 m wide corridor, 40 m long along x.
std::vector<Segment> CorridorWalls() {
  return {{Eigen::Vector2d(-20.0, -1.0), Eigen::Vector2d(20.0, -1.0)},
          {Eigen::Vector2d(-20.0, 1.0), Eigen::Vector2d(20.0, 1.0)}};
}

// As loop closure sees a scan: adaptively voxel-filtered to ~100 points (max voxel 0.9 m).
sensor::PointCloud2d LoopClosureCloud(const std::vector<Segment>& walls,
                                      const common::Rigid2d& T_world_scan) {
  sensor::AdaptiveVoxelFilterOptions options;
  options.max_length_m = 0.9f;
  options.min_num_points = 100;
  return sensor::AdaptiveVoxelFilter(test_world::CastCloud(walls, T_world_scan, 360, 12.0),
                                     options);
}

TEST(ScanInformation2DTest, ACorridorHoldsAMatchAcrossItButNotAlongIt) {
  // Mid-corridor, turned 20 degrees: 12 m of range sees two parallel lines and no end.
  const sensor::PointCloud2d cloud =
      LoopClosureCloud(CorridorWalls(), common::Rigid2d(0.0, 0.1, common::DegToRad(20.0)));
  ASSERT_GE(cloud.size(), 100u);
  const ScanInformation2D info = ComputeScanInformation2D(cloud);
  EXPECT_GT(info.points_on_lines, static_cast<int>(cloud.size()) / 2);
  EXPECT_GT(info.strongest_translation, 0.0);
  EXPECT_LT(info.TranslationRatio(), 0.01);
  // The weak direction is the corridor's axis, turned into the scan's frame.
  const double axis_rad = -common::DegToRad(20.0);
  EXPECT_GT(std::abs(info.weakest_direction.dot(
                Eigen::Vector2d(std::cos(axis_rad), std::sin(axis_rad)))),
            0.99);
  // A straight corridor: sliding along it does not turn.
  EXPECT_EQ(info.weakest_turn_rad_per_m, 0.0);
}

// The turn per metre forward round a ring corridor between walls of radius inner_m and
// outer_m, as a scan on the circle of radius_m facing along it measures it. Every point of the
// ring looks the same, so the scan holds a match across the ring only.
double ForwardTurnRoundRing(double inner_m, double outer_m, double radius_m) {
  const sensor::PointCloud2d cloud = LoopClosureCloud(
      test_world::RingCorridorWalls(inner_m, outer_m), test_world::RingPose(radius_m, 0.3));
  EXPECT_GE(cloud.size(), 100u);
  const ScanInformation2D info = ComputeScanInformation2D(cloud);
  EXPECT_LT(info.TranslationRatio(), 0.01);
  // Along the ring is the scan's x axis; forward round it (anticlockwise) turns left.
  EXPECT_GT(std::abs(info.weakest_direction.x()), 0.99);
  return info.weakest_direction.x() > 0.0 ? info.weakest_turn_rad_per_m
                                          : -info.weakest_turn_rad_per_m;
}

TEST(ScanInformation2DTest, ARingCorridorSlidesRoundItsCentreAndTurnsWithIt) {
  // Radius 7 m between walls at 6 and 8 m: a match slides round the centre, turning 1/7 rad
  // per metre.
  EXPECT_NEAR(ForwardTurnRoundRing(6.0, 8.0, 7.0), 1.0 / 7.0, 0.01);
}

TEST(ScanInformation2DTest, AGentlyCurvedCorridorTurnsWithItToo) {
  // Radius 25 m: a turn of 0.04 rad per metre, which a threshold on the turn itself (0.05)
  // took for a straight corridor, so a match slid 3 m along kept a heading 7 degrees off.
  EXPECT_NEAR(ForwardTurnRoundRing(24.0, 26.0, 25.0), 1.0 / 25.0, 0.004);
}

TEST(ScanInformation2DTest, DoorFramesAlongAStraightCorridorDoNotMakeItTurn) {
  // The corridor's north wall has a 1 m door every 3 m, each with 0.3 m jambs: a few points off
  // the two long lines, on one side only.
  std::vector<Segment> walls = {{Eigen::Vector2d(-20.0, -1.0), Eigen::Vector2d(20.0, -1.0)}};
  for (int k = -7; k < 7; ++k) {
    const double door_start = 3.0 * k;
    const double door_end = door_start + 1.0;
    walls.push_back({Eigen::Vector2d(door_end, 1.0), Eigen::Vector2d(door_start + 3.0, 1.0)});
    walls.push_back({Eigen::Vector2d(door_start, 1.0), Eigen::Vector2d(door_start, 1.3)});
    walls.push_back({Eigen::Vector2d(door_end, 1.0), Eigen::Vector2d(door_end, 1.3)});
  }
  for (const double x_m : {-0.7, 0.2, 1.1}) {
    const ScanInformation2D info =
        ComputeScanInformation2D(LoopClosureCloud(walls, common::Rigid2d(x_m, 0.1, 0.05)));
    EXPECT_EQ(info.weakest_turn_rad_per_m, 0.0) << "at x " << x_m;
  }
}

TEST(ScanInformation2DTest, ARoomHoldsAMatchEveryWay) {
  const sensor::PointCloud2d cloud =
      LoopClosureCloud(test_world::SmallRoomWalls(), common::Rigid2d(-1.0, -0.5, 0.3));
  const ScanInformation2D info = ComputeScanInformation2D(cloud);
  EXPECT_GT(info.TranslationRatio(), 0.3);
  EXPECT_GT(info.information(2, 2), 0.0);
}

TEST(ScanInformation2DTest, TheCorridorsEndGivesTheAxisBack) {
  std::vector<Segment> closed = CorridorWalls();
  closed.push_back({Eigen::Vector2d(-20.0, -1.0), Eigen::Vector2d(-20.0, 1.0)});
  // 8 m from the closed west end, which the scan reaches.
  const common::Rigid2d T_world_scan(-12.0, 0.0, 0.0);
  const ScanInformation2D open_info =
      ComputeScanInformation2D(LoopClosureCloud(CorridorWalls(), T_world_scan));
  const ScanInformation2D closed_info =
      ComputeScanInformation2D(LoopClosureCloud(closed, T_world_scan));
  EXPECT_LT(open_info.TranslationRatio(), 0.01);
  EXPECT_GT(closed_info.TranslationRatio(), 0.02);
}

// A grid covering x, y in [-20, 20] m at 5 cm holding `walls` (cells away from them unknown).
ProbabilityGrid GridOf(const std::vector<Segment>& walls) {
  MapLimits limits;
  limits.resolution_m = 0.05;
  limits.origin_m = Eigen::Vector2d(-20.0, -20.0);
  limits.num_x_cells = 800;
  limits.num_y_cells = 800;
  return test_world::DrawWalls(limits, walls, 0.3);
}

TEST(ScanInformation2DTest, StructureTheSubmapDoesNotHoldMeasuresNothing) {
  // A scan at a corner (simulator corridor, node 863 of issue 17): the corridor along x and a
  // second one going north from its west end. A submap that saw only the first corridor holds
  // the match across it only, though the scan alone holds it every way.
  const std::vector<Segment> first = {{Eigen::Vector2d(-2.0, -1.0), Eigen::Vector2d(20.0, -1.0)},
                                      {Eigen::Vector2d(0.0, 1.0), Eigen::Vector2d(20.0, 1.0)}};
  std::vector<Segment> both = first;
  both.push_back({Eigen::Vector2d(-2.0, -1.0), Eigen::Vector2d(-2.0, 20.0)});
  both.push_back({Eigen::Vector2d(0.0, 1.0), Eigen::Vector2d(0.0, 20.0)});
  const common::Rigid2d T_world_scan(-1.0, 0.0, common::DegToRad(-60.0));
  const sensor::PointCloud2d cloud = LoopClosureCloud(both, T_world_scan);
  ASSERT_GT(ComputeScanInformation2D(cloud).TranslationRatio(), 0.05);
  const ScanInformation2D seen_both =
      ComputeMatchedScanInformation2D(GridOf(both), T_world_scan, cloud, kConfirmingProbability);
  const ScanInformation2D seen_first =
      ComputeMatchedScanInformation2D(GridOf(first), T_world_scan, cloud, kConfirmingProbability);
  EXPECT_GT(seen_both.TranslationRatio(), 0.05);
  EXPECT_LT(seen_first.TranslationRatio(), 0.02);
  // Along the first corridor's axis, turned into the scan's frame.
  const double axis_rad = common::DegToRad(60.0);
  EXPECT_GT(std::abs(seen_first.weakest_direction.dot(
                Eigen::Vector2d(std::cos(axis_rad), std::sin(axis_rad)))),
            0.99);
}

TEST(ScanInformation2DTest, GapsInWhatTheSubmapHoldsInventNoStructure) {
  // Regression (simulator corridor, 1.8 m between its walls, node 13 in submap 13): a submap
  // holding the walls in pieces confirmed stretches of the scan with gaps between them; lines
  // fitted among the confirmed points alone joined points across the corridor and made the
  // match look held along it.
  const std::vector<Segment> walls = {{Eigen::Vector2d(-20.0, -0.8), Eigen::Vector2d(20.0, -0.8)},
                                      {Eigen::Vector2d(-20.0, 0.8), Eigen::Vector2d(20.0, 0.8)}};
  std::vector<Segment> pieces;
  for (double x = -20.0; x < 20.0; x += 3.0) {
    pieces.push_back({Eigen::Vector2d(x, -0.8), Eigen::Vector2d(x + 0.5, -0.8)});
    pieces.push_back({Eigen::Vector2d(x + 1.5, 0.8), Eigen::Vector2d(x + 2.0, 0.8)});
  }
  const common::Rigid2d T_world_scan(0.0, 0.1, common::DegToRad(20.0));
  const sensor::PointCloud2d cloud = LoopClosureCloud(walls, T_world_scan);
  const ScanInformation2D info =
      ComputeMatchedScanInformation2D(GridOf(pieces), T_world_scan, cloud, kConfirmingProbability);
  EXPECT_GT(info.points_on_lines, 0);
  EXPECT_LT(info.TranslationRatio(), 0.01);
}

TEST(ScanInformation2DTest, ScatteredPointsOnNoLineGiveNothing) {
  // Three far-apart points: no point has neighbours within 2 m.
  const sensor::PointCloud2d cloud = {Eigen::Vector2f(0.f, 5.f), Eigen::Vector2f(5.f, 0.f),
                                      Eigen::Vector2f(-5.f, 0.f)};
  const ScanInformation2D info = ComputeScanInformation2D(cloud);
  EXPECT_EQ(info.points_on_lines, 0);
  EXPECT_EQ(info.TranslationRatio(), 0.0);
  EXPECT_TRUE(info.information.isZero());
  EXPECT_EQ(ComputeScanInformation2D({}).TranslationRatio(), 0.0);
}

}  // namespace
}  // namespace mapping
}  // namespace fusemap
