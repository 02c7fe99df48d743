#ifndef FUSEMAP_TEST_TESTING_SYNTHETIC_ROOM_H_
#define FUSEMAP_TEST_TESTING_SYNTHETIC_ROOM_H_

// A small 2D world for SLAM tests: wall segments, an exact ray caster and a 360-beam scanner.
// Header-only and test-only; the simulator (sim/) is the full-scale version.

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "fusemap/common/math.h"
#include "fusemap/common/rigid_transform.h"
#include "fusemap/sensor/range_data_builder.h"
#include "fusemap/sensor/sensor_types.h"

namespace fusemap {
namespace test_world {

constexpr double kRangeMaxM = 12.0;
constexpr int kNumBeams = 360;
// The arc that ArcPose follows: around the room's island at (6, 4).
constexpr double kArcRadiusM = 2.5;

struct Segment {
  Eigen::Vector2d a, b;
};

inline void AddBox(double x0, double y0, double x1, double y1, std::vector<Segment>* walls) {
  walls->push_back({{x0, y0}, {x1, y0}});
  walls->push_back({{x1, y0}, {x1, y1}});
  walls->push_back({{x1, y1}, {x0, y1}});
  walls->push_back({{x0, y1}, {x0, y0}});
}

// A 12 m x 8 m room with an island in the middle and two corner boxes (asymmetric, so that
// scan matching has a unique answer).
inline std::vector<Segment> Room() {
  std::vector<Segment> walls;
  AddBox(0.0, 0.0, 12.0, 8.0, &walls);
  AddBox(5.5, 3.5, 6.5, 4.5, &walls);
  AddBox(10.5, 0.5, 11.5, 1.5, &walls);
  AddBox(1.0, 6.5, 2.0, 7.5, &walls);
  return walls;
}

// Nearest intersection of the ray p + t d (t > 0) with any wall, or infinity.
inline double CastRay(const std::vector<Segment>& walls, const Eigen::Vector2d& p,
                      const Eigen::Vector2d& d) {
  double best = std::numeric_limits<double>::infinity();
  for (const Segment& s : walls) {
    const Eigen::Vector2d e = s.b - s.a;
    const double denom = d.x() * e.y() - d.y() * e.x();
    if (std::abs(denom) < 1e-12) continue;
    const Eigen::Vector2d w = s.a - p;
    const double t = (w.x() * e.y() - w.y() * e.x()) / denom;
    const double u = (w.x() * d.y() - w.y() * d.x()) / denom;
    if (t > 1e-9 && u >= 0.0 && u <= 1.0) best = std::min(best, t);
  }
  return best;
}

// A 360-beam, 360 deg scan at `pose` (world frame). With `rng`, each range gets uniform noise
// of +-noise_m (std::mt19937's output is specified by the standard and the mapping to metres
// is ours, so the noise is the same on every platform).
inline sensor::LaserScan SimulateScan(const std::vector<Segment>& walls,
                                      const common::Rigid2d& pose, double stamp_s,
                                      double noise_m = 0.0, std::mt19937* rng = nullptr) {
  sensor::LaserScan scan;
  scan.stamp_s = stamp_s;
  scan.angle_min_rad = static_cast<float>(-common::kPi);
  scan.angle_increment_rad = static_cast<float>(2.0 * common::kPi / kNumBeams);
  scan.range_min_m = 0.1f;
  scan.range_max_m = static_cast<float>(kRangeMaxM);
  for (int i = 0; i < kNumBeams; ++i) {
    const double angle = pose.angle_rad() + scan.angle_min_rad + i * scan.angle_increment_rad;
    double r = CastRay(walls, pose.translation(), {std::cos(angle), std::sin(angle)});
    if (rng != nullptr) r += noise_m * (2.0 * ((*rng)() / 4294967296.0) - 1.0);
    scan.ranges_m.push_back(r < kRangeMaxM ? static_cast<float>(r)
                                           : std::numeric_limits<float>::infinity());
  }
  return scan;
}

// Range data of SimulateScan in the scanner frame, with the default range gate.
inline sensor::RangeData SimulateRangeData(const std::vector<Segment>& walls,
                                           const common::Rigid2d& pose) {
  return sensor::RangeDataFromScan(SimulateScan(walls, pose, 0.0), sensor::RangeGateOptions());
}

// Pose `i` on the counter-clockwise circle of radius kArcRadiusM around the island, step_m
// apart, heading along the circle.
inline common::Rigid2d ArcPose(int i, double step_m) {
  const double theta = step_m * i / kArcRadiusM;
  return common::Rigid2d(6.0 + kArcRadiusM * std::sin(theta), 4.0 - kArcRadiusM * std::cos(theta),
                         theta);
}

// A circular wall round the origin as a regular polygon of `sides` segments, appended to walls.
inline void AddCircle(double radius_m, int sides, std::vector<Segment>* walls) {
  for (int i = 0; i < sides; ++i) {
    const double a0 = 2.0 * common::kPi * i / sides, a1 = 2.0 * common::kPi * (i + 1) / sides;
    walls->push_back({Eigen::Vector2d(radius_m * std::cos(a0), radius_m * std::sin(a0)),
                      Eigen::Vector2d(radius_m * std::cos(a1), radius_m * std::sin(a1))});
  }
}

// A ring corridor round the origin between radii inner_m and outer_m, each wall a 180-gon
// (sagitta under 1 mm at 8 m): its plain curved walls look the same from every point of it.
inline std::vector<Segment> RingCorridorWalls(double inner_m, double outer_m) {
  std::vector<Segment> walls;
  AddCircle(inner_m, 180, &walls);
  AddCircle(outer_m, 180, &walls);
  return walls;
}

// The pose on the circle of radius radius_m round the origin at angle_rad, facing along it
// anticlockwise.
inline common::Rigid2d RingPose(double radius_m, double angle_rad) {
  return common::Rigid2d(radius_m * std::cos(angle_rad), radius_m * std::sin(angle_rad),
                         angle_rad + 0.5 * common::kPi);
}

}  // namespace test_world
}  // namespace fusemap

#endif  // FUSEMAP_TEST_TESTING_SYNTHETIC_ROOM_H_
