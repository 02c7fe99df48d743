#include "fusemap/sim/simulation.h"

#include <gtest/gtest.h>

#include <cmath>

#include "fusemap/sim/world_loader.h"

namespace fusemap {
namespace sim {
namespace {

World LoadHall() {
  World world;
  std::string error;
  EXPECT_TRUE(LoadWorldFile(std::string(FUSEMAP_SOURCE_DIR) + "/data/worlds/hall.yaml", &world, &error)) << error;
  return world;
}

SimulationOptions SmallOptions(uint64_t seed) {
  SimulationOptions options;
  options.seed = seed;
  options.seconds = 2.0;
  options.rgbd.width = 160;
  options.rgbd.height = 120;
  options.rgbd.fx = options.rgbd.fy = 131.25;
  options.rgbd.cx = 79.5;
  options.rgbd.cy = 59.5;
  return options;
}

TEST(WorldLoaderTest, LoadsDefaultHall) {
  const World world = LoadHall();
  EXPECT_EQ(world.name, "hall");
  EXPECT_EQ(world.tags.size(), 19u);
  EXPECT_EQ(world.people.size(), 2u);
  EXPECT_EQ(world.robot.waypoints_m.size(), 4u);
  EXPECT_GE(world.prisms.size(), 8u + 3u + 8u);
}

TEST(WorldLoaderTest, ErrorsNameLineAndKey) {
  World world;
  std::string error;
  EXPECT_FALSE(LoadWorldFromString("name: x\nwalls:\n  - {from: [0, 0], to: [1, 0], thikness_m: 1}\n",
                                   "test.yaml", &world, &error));
  EXPECT_NE(error.find("test.yaml:3:"), std::string::npos) << error;
  EXPECT_NE(error.find("thikness_m"), std::string::npos) << error;
  EXPECT_FALSE(LoadWorldFromString("robot:\n  waypoints: [[0, 0], [1, 0]]\n", "r.yaml", &world, &error));
  EXPECT_NE(error.find("at least 3 waypoints"), std::string::npos) << error;
  EXPECT_FALSE(LoadWorldFromString("ceiling_height_m: abc\n", "c.yaml", &world, &error));
  EXPECT_NE(error.find("c.yaml:1:"), std::string::npos) << error;
}

TEST(SimulationOptionsTest, ParsesKeysAndRejectsOutOfRange) {
  std::string error;
  auto reader = common::ConfigReader::FromString(
      "seconds: 12\nseed: 4\nlaser: {rate_hz: 40, num_beams: 541}\nrgbd: {rate_hz: 25}\n", "opts", &error);
  ASSERT_TRUE(reader) << error;
  const SimulationOptions options = ParseSimulationOptions(*reader);
  EXPECT_TRUE(reader->Finish(&error)) << error;
  EXPECT_DOUBLE_EQ(options.seconds, 12.0);
  EXPECT_EQ(options.seed, 4u);
  EXPECT_DOUBLE_EQ(options.laser.rate_hz, 40.0);
  EXPECT_EQ(options.laser.num_beams, 541);
  EXPECT_DOUBLE_EQ(options.rgbd.rate_hz, 25.0);
  auto bad = common::ConfigReader::FromString("laser: {range_max_m: -1}\n", "bad", &error);
  ASSERT_TRUE(bad) << error;
  ParseSimulationOptions(*bad);
  EXPECT_FALSE(bad->Finish(&error));
  EXPECT_EQ(error, "bad:1: key 'laser.range_max_m': must be > range_min_m");
}

// Issue 16: each bad value is reported once, against its own key path and line.
TEST(SimulationOptionsTest, EachBadValueNamesItsKeyPathAndLine) {
  const struct {
    const char* yaml;
    const char* error;
  } cases[] = {
      {"seed: 1\nseconds: 0\n", "opts:2: key 'seconds': must be in (0, 86400]"},
      {"ground_truth_rate_hz: -1\n", "opts:1: key 'ground_truth_rate_hz': must be in (0, 10000]"},
      {"laser:\n  num_beams: 1\n", "opts:2: key 'laser.num_beams': must be >= 2"},
      {"odometry:\n  rate_hz: 0\n", "opts:2: key 'odometry.rate_hz': must be > 0"},
      {"imu:\n  rate_hz: 0\n", "opts:2: key 'imu.rate_hz': must be > 0"},
      {"rgbd:\n  rate_hz: 25\n  height: 4\n", "opts:3: key 'rgbd.height': must be in [8, 4096]"},
  };
  for (const auto& c : cases) {
    std::string error;
    auto reader = common::ConfigReader::FromString(c.yaml, "opts", &error);
    ASSERT_TRUE(reader) << error;
    ParseSimulationOptions(*reader);
    EXPECT_FALSE(reader->Finish(&error)) << c.yaml;
    EXPECT_EQ(error, c.error) << c.yaml;
  }
  SimulationOptions options;
  options.rgbd_enabled = true;
  options.rgbd.fx = 0.0;
  std::string error;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_EQ(error, "rgbd.fx must be > 0");
}

TEST(TrajectoryTest, SmoothLoopWithinLimits) {
  const World world = LoadHall();
  const WaypointTrajectory trajectory(world.robot);
  // Rectangle 24 x 11.2 m with four 1.2 m arcs: 2 * (24 + 11.2) - 8 * 1.2 + 2 * pi * 1.2.
  EXPECT_NEAR(trajectory.loop_length_m(), 70.4 - 9.6 + 2 * M_PI * 1.2, 1e-6);
  EXPECT_DOUBLE_EQ(trajectory.StateAt(0.0).speed_mps, 0.0);
  double max_speed = 0.0;
  RobotState previous = trajectory.StateAt(0.0);
  for (double t = 0.01; t <= trajectory.duration_s(); t += 0.01) {
    const RobotState state = trajectory.StateAt(t);
    max_speed = std::max(max_speed, state.speed_mps);
    EXPECT_LE(state.speed_mps, world.robot.max_speed_mps + 1e-9);
    // Lateral limit holds at the 2 cm path samples; in between, speed is interpolated: 5 %.
    EXPECT_LE(std::abs(state.speed_mps * state.yaw_rate_radps), 1.05 * world.robot.max_lateral_accel_mps2);
    // Continuity: no jumps between 10 ms samples.
    EXPECT_LE((state.T_world_base.translation() - previous.T_world_base.translation()).norm(), 0.021);
    EXPECT_LE(std::abs(common::NormalizeAngle(state.T_world_base.angle_rad() - previous.T_world_base.angle_rad())), 0.02);
    previous = state;
  }
  EXPECT_GT(max_speed, 1.9);
  // 1.5 laps end at rest half a loop from the start (2.7, 1.3): by symmetry of the rectangle,
  // at the matching point after the opposite corner, (24.3, 12.5), heading -x.
  const RobotState end = trajectory.StateAt(trajectory.duration_s());
  EXPECT_DOUBLE_EQ(end.speed_mps, 0.0);
  EXPECT_NEAR(end.T_world_base.x(), 24.3, 0.02);
  EXPECT_NEAR(end.T_world_base.y(), 12.5, 0.02);
  EXPECT_NEAR(std::abs(end.T_world_base.angle_rad()), M_PI, 0.02);
}

TEST(SimulationTest, SameSeedSameOutputDifferentSeedDifferent) {
  std::string error;
  auto a = Simulation::Create(LoadHall(), SmallOptions(1), &error);
  auto b = Simulation::Create(LoadHall(), SmallOptions(1), &error);
  auto c = Simulation::Create(LoadHall(), SmallOptions(2), &error);
  ASSERT_TRUE(a && b && c) << error;
  EXPECT_EQ(a->Laser(7).ranges_m, b->Laser(7).ranges_m);
  EXPECT_NE(a->Laser(7).ranges_m, c->Laser(7).ranges_m);
  const sensor::RgbdFrame fa = a->Rgbd(3), fb = b->Rgbd(3), fc = c->Rgbd(3);
  EXPECT_EQ(fa.depth_mm, fb.depth_mm);
  EXPECT_EQ(fa.color_rgb, fb.color_rgb);
  EXPECT_NE(fa.depth_mm, fc.depth_mm);
  OdometrySimulator oa = a->MakeOdometrySimulator(), ob = b->MakeOdometrySimulator();
  double v, w;
  for (int i = 0; i < 10; ++i) {
    const double t = 0.5 + 0.02 * i;
    EXPECT_EQ(oa.Step(t, a->Truth(t), &v, &w).pose.DebugString(), ob.Step(t, b->Truth(t), &v, &w).pose.DebugString());
  }
}

TEST(SimulationTest, OdometryDriftsButStaysClose) {
  std::string error;
  auto simulation = Simulation::Create(LoadHall(), SmallOptions(3), &error);
  ASSERT_TRUE(simulation) << error;
  OdometrySimulator odometry = simulation->MakeOdometrySimulator();
  ImuSimulator imu = simulation->MakeImuSimulator();
  const common::Rigid2d start = simulation->Truth(0.0).T_world_base;
  sensor::OdometryData last;
  double v, w, mean_az = 0.0;
  for (int i = 0; i <= 1000; ++i) {  // 20 s at 50 Hz.
    const double t = i * 0.02;
    last = odometry.Step(t, simulation->Truth(t), &v, &w);
    mean_az += imu.Step(t, simulation->Truth(t)).linear_acceleration_mps2.z() / 1001.0;
  }
  const common::Rigid2d truth = start.inverse() * simulation->Truth(20.0).T_world_base;
  const double error_m = (last.pose.translation() - truth.translation()).norm();
  EXPECT_GT(error_m, 1e-3);  // Noisy, so not exact...
  EXPECT_LT(error_m, 0.05 * truth.translation().norm() + 0.2);  // ...but a few percent at most.
  EXPECT_NEAR(mean_az, 9.81, 0.2);
}

TEST(WorldLoaderTest, PosterBandAndLightingPhases) {
  World world;
  std::string error;
  const std::string base =
      "robot: {waypoints: [[0, 0], [10, 0], [10, 4]], laps: 2}\n"
      "walls:\n  - {from: [0, 1], to: [5, 1], texture: {kind: poster, band_m: [0.1, 0.9]}}\n";
  ASSERT_TRUE(LoadWorldFromString(base + "lighting:\n  - {from_lap: 1, gain: 0.6, bias: 12, "
                                         "noise_std: 6}\n",
                                  "w.yaml", &world, &error))
      << error;
  EXPECT_DOUBLE_EQ(world.prisms[0].side_textures[1].band_bottom_m, 0.1);
  EXPECT_DOUBLE_EQ(world.prisms[0].side_textures[1].band_top_m, 0.9);
  ASSERT_EQ(world.lighting.size(), 1u);
  EXPECT_DOUBLE_EQ(world.lighting[0].gain, 0.6);
  EXPECT_FALSE(LoadWorldFromString(base + "lighting:\n  - {from_lap: 1}\n  - {from_lap: 0.5}\n",
                                   "w.yaml", &world, &error));
  EXPECT_NE(error.find("w.yaml:6: lighting phases need increasing from_lap"), std::string::npos)
      << error;
  EXPECT_FALSE(LoadWorldFromString(
      "walls:\n  - {from: [0, 1], to: [5, 1], texture: {kind: poster, band_m: [1, 0.5]}}\n",
      "b.yaml", &world, &error));
  EXPECT_NE(error.find("b.yaml:2: band_m"), std::string::npos) << error;
}

// A world may fix the wheel odometry's speed scale (a robot known to read 2 % long): the
// distance it reports is then the driven one times that, up to the speed noise.
TEST(SimulationTest, WorldFixesOdometrySpeedScale) {
  World world;
  std::string error;
  const std::string route = "robot: {waypoints: [[0, 0], [20, 0], [20, 10], [0, 10]], laps: 1";
  ASSERT_TRUE(
      LoadWorldFromString(route + ", odometry_speed_scale: 1.02}\n", "s.yaml", &world, &error))
      << error;
  EXPECT_DOUBLE_EQ(world.robot.odometry_speed_scale, 1.02);
  const auto distances = [](const World& w) {
    std::string create_error;
    auto simulation = Simulation::Create(w, SmallOptions(5), &create_error);
    EXPECT_TRUE(simulation) << create_error;
    OdometrySimulator odometry = simulation->MakeOdometrySimulator();
    double v, w_radps, measured_m = 0.0, driven_m = 0.0;
    for (int i = 0; i <= 500; ++i) {  // 10 s at 50 Hz.
      const double t = i * 0.02;
      odometry.Step(t, simulation->Truth(t), &v, &w_radps);
      measured_m += v * 0.02;
      driven_m += simulation->Truth(t).speed_mps * 0.02;
    }
    return std::make_pair(measured_m, driven_m);
  };
  const auto [fixed_m, fixed_driven_m] = distances(world);
  ASSERT_GT(fixed_driven_m, 5.0);
  EXPECT_NEAR(fixed_m / fixed_driven_m, 1.02, 0.002);
  // Without the key the scale is drawn (seed 5: not 1.02).
  World drawn = world;
  drawn.robot.odometry_speed_scale = 0.0;
  const auto [drawn_m, drawn_driven_m] = distances(drawn);
  EXPECT_GT(std::abs(drawn_m / drawn_driven_m - 1.02), 0.002);
  EXPECT_FALSE(
      LoadWorldFromString(route + ", odometry_speed_scale: 3}\n", "s.yaml", &world, &error));
  EXPECT_NE(error.find("odometry_speed_scale"), std::string::npos) << error;
}

TEST(SimulationTest, LightingPhaseStartsAtItsLap) {
  World world = LoadHall();
  world.robot.laps = 2.0;
  world.lighting = {LightingPhase{1.0, 0.5, 0.0, 0.0}};
  std::string error;
  auto simulation = Simulation::Create(world, SmallOptions(1), &error);
  ASSERT_TRUE(simulation) << error;
  const WaypointTrajectory& trajectory = simulation->trajectory();
  EXPECT_DOUBLE_EQ(trajectory.TimeAtLaps(0.0), 0.0);
  EXPECT_DOUBLE_EQ(trajectory.TimeAtLaps(5.0), trajectory.duration_s());
  const double lap_s = trajectory.TimeAtLaps(1.0);
  // About halfway through a 2-lap drive that starts and ends at rest (the speed profile is not
  // symmetric: the first leg starts after a corner, the last one ends before it).
  EXPECT_NEAR(lap_s, 0.5 * trajectory.duration_s(), 0.5);
  // After one lap the robot is back where it started.
  EXPECT_LT((trajectory.StateAt(lap_s).T_world_base.translation() -
             trajectory.StateAt(0.0).T_world_base.translation()).norm(), 0.02);
  EXPECT_DOUBLE_EQ(simulation->LightingAt(lap_s - 0.01).gain, 1.0);
  EXPECT_DOUBLE_EQ(simulation->LightingAt(lap_s + 0.01).gain, 0.5);
}

}  // namespace
}  // namespace sim
}  // namespace fusemap
