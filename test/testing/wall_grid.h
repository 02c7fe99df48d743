#ifndef FUSEMAP_TEST_TESTING_WALL_GRID_H_
#define FUSEMAP_TEST_TESTING_WALL_GRID_H_

// Probability grids drawn directly from wall segments, and point clouds ray-cast against the
// same walls, for scan-matcher tests that need a known map without running the inserter.

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "fusemap/mapping/probability_grid.h"
#include "testing/synthetic_room.h"

namespace fusemap {
namespace test_world {

inline double DistanceToSegment(const Eigen::Vector2d& p, const Segment& s) {
  const Eigen::Vector2d ab = s.b - s.a;
  const double t = std::clamp((p - s.a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (s.a + t * ab - p).norm();
}

// Walls drawn with a Gaussian profile (sigma one 5 cm cell), as many insertions would leave
// them. Cells farther than cutoff_m from every wall are left unknown.
inline mapping::ProbabilityGrid DrawWalls(const mapping::MapLimits& limits,
                                          const std::vector<Segment>& walls,
                                          double cutoff_m = std::numeric_limits<double>::max()) {
  mapping::ProbabilityGrid grid(limits);
  for (int y = 0; y < limits.num_y_cells; ++y) {
    for (int x = 0; x < limits.num_x_cells; ++x) {
      const Eigen::Array2i cell(x, y);
      double d = std::numeric_limits<double>::max();
      for (const Segment& s : walls) d = std::min(d, DistanceToSegment(limits.GetCellCenter(cell), s));
      if (d < cutoff_m) {
        grid.SetProbability(cell, static_cast<float>(0.1 + 0.8 * std::exp(-d * d / (2 * 0.05 * 0.05))));
      }
    }
  }
  return grid;
}

// Returns (in the tracking frame) of `num_beams` beams over 360 deg from T_grid_tracking;
// beams that hit nothing closer than range_max_m give no point.
inline sensor::PointCloud2d CastCloud(const std::vector<Segment>& walls,
                                      const common::Rigid2d& T_grid_tracking, int num_beams,
                                      double range_max_m) {
  sensor::PointCloud2d cloud;
  for (int i = 0; i < num_beams; ++i) {
    const double beam_rad = 2.0 * common::kPi * i / num_beams;
    const Eigen::Vector2d beam(std::cos(beam_rad), std::sin(beam_rad));
    const double range_m =
        CastRay(walls, T_grid_tracking.translation(), T_grid_tracking.rotation() * beam);
    if (range_m < range_max_m) cloud.push_back((range_m * beam).cast<float>());
  }
  return cloud;
}

// A 7.95 m x 5.95 m room with a 1 m pillar; wall lines pass through cell centres of a 5 cm
// grid with origin (-5, -4).
inline std::vector<Segment> SmallRoomWalls() {
  std::vector<Segment> walls;
  AddBox(-3.975, -2.975, 3.975, 2.975, &walls);
  AddBox(1.025, 0.525, 2.025, 1.525, &walls);
  return walls;
}

inline mapping::ProbabilityGrid MakeSmallRoomGrid() {
  mapping::MapLimits limits;
  limits.resolution_m = 0.05;
  limits.origin_m = Eigen::Vector2d(-5.0, -4.0);
  limits.num_x_cells = 200;
  limits.num_y_cells = 160;
  return DrawWalls(limits, SmallRoomWalls());
}

}  // namespace test_world
}  // namespace fusemap

#endif  // FUSEMAP_TEST_TESTING_WALL_GRID_H_
