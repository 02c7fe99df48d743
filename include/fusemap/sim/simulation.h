#ifndef FUSEMAP_SIM_SIMULATION_H_
#define FUSEMAP_SIM_SIMULATION_H_

#include <cstdint>
#include <memory>
#include <string>

#include "fusemap/common/config_reader.h"
#include "fusemap/sensor/rgbd_frame.h"
#include "fusemap/sensor/sensor_types.h"
#include "fusemap/sim/floor_tags.h"
#include "fusemap/sim/laser_simulator.h"
#include "fusemap/sim/odometry_imu_simulator.h"
#include "fusemap/sim/rgbd_renderer.h"
#include "fusemap/sim/trajectory.h"
#include "fusemap/sim/world.h"

namespace fusemap {
namespace sim {

struct SimulationOptions {
  double seconds = 60.0;
  uint64_t seed = 1;
  // Stamps are start_time_s + simulated time: a fixed epoch keeps output independent of the clock.
  double start_time_s = 1700000000.0;
  double ground_truth_rate_hz = 100.0;
  bool rgbd_enabled = true;
  LaserOptions laser;
  OdometryOptions odometry;
  ImuOptions imu;
  RgbdCameraOptions rgbd;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};
// Keys: seconds, seed, start_time_s, ground_truth_rate_hz, rgbd_enabled and the children
// laser, odometry (rate_hz only), imu (rate_hz only), rgbd.
SimulationOptions ParseSimulationOptions(common::ConfigReader& reader);

// A world, the robot's drive through it and the sensor models. Message i of a periodic sensor
// is taken at simulated time i / rate_hz for 0 <= i < count. Laser, RGB-D and ground truth
// are pure functions of the index (noise seeded per message), so they may be produced in any
// order or thread; odometry and IMU drift, so their simulators are stepped in order.
class Simulation {
 public:
  // Validates options and the world's tags; nullptr and *error on failure.
  static std::unique_ptr<Simulation> Create(World world, const SimulationOptions& options,
                                            std::string* error);

  const World& world() const { return world_; }
  const SimulationOptions& options() const { return options_; }
  const WaypointTrajectory& trajectory() const { return trajectory_; }
  const FloorTags& floor_tags() const { return floor_tags_; }

  static int Count(double rate_hz, double seconds);
  double Stamp(double sim_time_s) const { return options_.start_time_s + sim_time_s; }

  RobotState Truth(double sim_time_s) const { return trajectory_.StateAt(sim_time_s); }
  sensor::LaserScan Laser(int index) const;
  // Rendered with the world's lighting phase at that time (see LightingAt).
  sensor::RgbdFrame Rgbd(int index) const;
  // The world's lighting phase in effect at sim_time_s (identity before the first one).
  LightingPhase LightingAt(double sim_time_s) const;
  OdometrySimulator MakeOdometrySimulator() const;
  ImuSimulator MakeImuSimulator() const;

 private:
  Simulation(World world, const SimulationOptions& options);

  World world_;
  SimulationOptions options_;
  WaypointTrajectory trajectory_;
  FloorTags floor_tags_;
  std::vector<double> lighting_start_s_;  // Per world_.lighting phase.
};

}  // namespace sim
}  // namespace fusemap

#endif  // FUSEMAP_SIM_SIMULATION_H_
