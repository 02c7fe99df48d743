#include "fusemap/sim/simulation.h"

#include <cmath>

#include "random.h"

namespace fusemap {
namespace sim {

void SimulationOptions::Check(common::OptionChecker* check) const {
  check->Require(seconds > 0.0 && seconds <= 24 * 3600.0, "seconds", "must be in (0, 86400]");
  check->Require(ground_truth_rate_hz > 0.0 && ground_truth_rate_hz <= 10000.0,
                 "ground_truth_rate_hz", "must be in (0, 10000]");
  check->Nested("laser", laser);
  check->Nested("odometry", odometry);
  check->Nested("imu", imu);
  if (rgbd_enabled) check->Nested("rgbd", rgbd);
}

bool SimulationOptions::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

SimulationOptions ParseSimulationOptions(common::ConfigReader& reader) {
  SimulationOptions o;
  reader.Get("seconds", &o.seconds);
  int seed = static_cast<int>(o.seed);
  reader.Get("seed", &seed);
  if (seed < 0) reader.AddError("seed", "must be >= 0");
  o.seed = static_cast<uint64_t>(std::max(0, seed));
  reader.Get("start_time_s", &o.start_time_s);
  reader.Get("ground_truth_rate_hz", &o.ground_truth_rate_hz);
  reader.Get("rgbd_enabled", &o.rgbd_enabled);
  o.laser = ParseLaserOptions(reader.Child("laser"));
  common::ConfigReader& odometry = reader.Child("odometry");
  odometry.Get("rate_hz", &o.odometry.rate_hz);
  odometry.CheckOptions(o.odometry);
  common::ConfigReader& imu = reader.Child("imu");
  imu.Get("rate_hz", &o.imu.rate_hz);
  imu.CheckOptions(o.imu);
  o.rgbd = ParseRgbdCameraOptions(reader.Child("rgbd"));
  reader.CheckOptions(o);
  return o;
}

std::unique_ptr<Simulation> Simulation::Create(World world, const SimulationOptions& options,
                                               std::string* error) {
  if (!options.IsValid(error)) return nullptr;
  if (world.robot.waypoints_m.size() < 3) {
    *error = "world '" + world.name + "' has fewer than 3 robot waypoints";
    return nullptr;
  }
  std::unique_ptr<Simulation> simulation(new Simulation(std::move(world), options));
  if (!simulation->floor_tags_.Init(simulation->world_.tags, error)) return nullptr;
  return simulation;
}

Simulation::Simulation(World world, const SimulationOptions& options)
    : world_(std::move(world)), options_(options), trajectory_(world_.robot) {
  for (const LightingPhase& phase : world_.lighting) {
    lighting_start_s_.push_back(trajectory_.TimeAtLaps(phase.from_lap));
  }
}

LightingPhase Simulation::LightingAt(double sim_time_s) const {
  LightingPhase lighting;
  for (size_t i = 0; i < lighting_start_s_.size() && lighting_start_s_[i] <= sim_time_s; ++i) {
    lighting = world_.lighting[i];
  }
  return lighting;
}

int Simulation::Count(double rate_hz, double seconds) {
  // Samples at i / rate strictly before `seconds` (tiny epsilon: 60 s at 25 Hz is 1500).
  return static_cast<int>(std::ceil(seconds * rate_hz - 1e-9));
}

sensor::LaserScan Simulation::Laser(int index) const {
  const double t = index / options_.laser.rate_hz;
  std::mt19937_64 rng = MakeRng(options_.seed, NoiseStream::kLaser, index);
  return SimulateLaserScan(PrismsAt(world_, t), Truth(t).T_world_base, Stamp(t), options_.laser, &rng);
}

sensor::RgbdFrame Simulation::Rgbd(int index) const {
  const double t = index / options_.rgbd.rate_hz;
  sensor::RgbdFrame frame = RenderRgbdFrame(world_, PrismsAt(world_, t), floor_tags_,
                                            Truth(t).T_world_base, Stamp(t), options_.rgbd,
                                            options_.seed, index);
  ApplyLighting(LightingAt(t), options_.seed, index, &frame.color_rgb);
  return frame;
}

OdometrySimulator Simulation::MakeOdometrySimulator() const {
  OdometryOptions odometry = options_.odometry;
  if (world_.robot.odometry_speed_scale > 0.0) {
    odometry.speed_scale = world_.robot.odometry_speed_scale;
  }
  return OdometrySimulator(odometry, options_.seed);
}

ImuSimulator Simulation::MakeImuSimulator() const { return ImuSimulator(options_.imu, options_.seed); }

}  // namespace sim
}  // namespace fusemap
