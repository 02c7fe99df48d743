#ifndef FUSEMAP_SIM_WORLD_H_
#define FUSEMAP_SIM_WORLD_H_

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace fusemap {
namespace sim {

// A procedural surface texture, sampled in metres on the surface (u along it, v up it), so
// the same wall looks the same from every viewpoint and ORB finds stable corners on it.
struct Texture {
  enum class Kind { kPlain, kBrick, kNoise, kStripes, kPoster, kChecker };
  Kind kind = Kind::kPlain;
  uint32_t seed = 0;
  double scale_m = 0.25;  // Characteristic feature size (brick height, stripe width, ...).
  Eigen::Vector3f color_a = Eigen::Vector3f(180.f, 180.f, 180.f);  // RGB 0..255
  Eigen::Vector3f color_b = Eigen::Vector3f(90.f, 90.f, 90.f);
  // Posters only: the height band they cover. A camera pitched down sees walls only below its
  // own height, so worlds meant for visual place recognition hang them low.
  double band_bottom_m = 0.7;
  double band_top_m = 2.0;
};

// A vertical extruded convex shape standing on the floor plane (z up, world frame): walls,
// pillars, furniture boxes and (moved over time) people. Rectangles have faces 0..3 = +x, +y,
// -x, -y of their own frame (rotated by yaw_rad about centre_m).
struct Prism {
  enum class Shape { kRectangle, kCircle };
  Shape shape = Shape::kRectangle;
  Eigen::Vector2d centre_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d half_size_m = Eigen::Vector2d(0.5, 0.5);  // Rectangle only.
  double yaw_rad = 0.0;                                      // Rectangle only.
  double radius_m = 0.5;                                     // Circle only.
  double z_min_m = 0.0;
  double z_max_m = 1.0;
  std::array<Texture, 4> side_textures;  // Circles use side_textures[0].
  Texture top_texture;
};

// A tag36h11 AprilTag lying flat on the floor. size_m is the edge of the black border square
// (the AprilTag convention used for pose estimation); a white margin of one cell surrounds it.
struct FloorTag {
  int id = 0;
  double x_m = 0.0;
  double y_m = 0.0;
  double yaw_rad = 0.0;
  double size_m = 0.4;
};

// A person walking back and forth along `path_m` at a constant speed, as a cylinder.
struct Person {
  std::vector<Eigen::Vector2d> path_m;
  double speed_mps = 1.0;
  double radius_m = 0.25;
  double height_m = 1.75;
  Texture texture;
};

// Axis-aligned floor-plan region where the depth camera returns nothing (glass, black cloth).
struct DepthDropoutZone {
  Eigen::Vector2d min_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d max_m = Eigen::Vector2d::Zero();
};

// How the camera sees the world from a point of the drive on: colour = gain * rendered + bias,
// plus Gaussian noise per pixel and channel (0..255 scale). A second lap under other lighting
// tests that visual place recognition survives a brightness and noise change.
struct LightingPhase {
  double from_lap = 0.0;  // Laps driven (arc length / loop length) when it starts.
  double gain = 1.0;
  double bias = 0.0;
  double noise_std = 0.0;
};

// The robot's route: a closed loop through the waypoints, driven laps times.
struct RobotPlan {
  std::vector<Eigen::Vector2d> waypoints_m;
  double max_speed_mps = 2.0;
  double max_accel_mps2 = 1.0;
  double max_lateral_accel_mps2 = 1.0;
  double turn_radius_m = 1.2;
  double laps = 1.5;
  // The wheel odometry's speed scale, when the world fixes it (a robot known to read long or
  // short); 0: drawn per run (OdometryOptions::speed_scale_error_stddev).
  double odometry_speed_scale = 0.0;
};

struct World {
  std::string name;
  double ceiling_height_m = 3.0;
  double floor_tile_m = 0.6;
  Eigen::Vector3f floor_color = Eigen::Vector3f(200.f, 195.f, 185.f);
  Eigen::Vector3f ceiling_color = Eigen::Vector3f(235.f, 235.f, 240.f);
  uint32_t floor_seed = 7;
  std::vector<Prism> prisms;  // Static geometry.
  std::vector<FloorTag> tags;
  std::vector<Person> people;
  std::vector<DepthDropoutZone> depth_dropout_zones;
  std::vector<LightingPhase> lighting;  // Increasing from_lap; none: rendered colours as is.
  RobotPlan robot;
};

// The cylinder standing for `person` at time stamp_s (deterministic in stamp_s).
Prism PersonPrismAt(const Person& person, double stamp_s);

// Static prisms followed by every person at stamp_s: the geometry sensors see at that time.
std::vector<Prism> PrismsAt(const World& world, double stamp_s);

}  // namespace sim
}  // namespace fusemap

#endif  // FUSEMAP_SIM_WORLD_H_
