#ifndef FUSEMAP_SIM_ODOMETRY_IMU_SIMULATOR_H_
#define FUSEMAP_SIM_ODOMETRY_IMU_SIMULATOR_H_

#include <cstdint>
#include <random>
#include <string>

#include "fusemap/common/option_checker.h"
#include "fusemap/sensor/sensor_types.h"
#include "fusemap/sim/trajectory.h"

namespace fusemap {
namespace sim {

// Wheel odometry: measured speed = (1 + scale error) * speed + noise, measured yaw rate = yaw rate
// + bias + noise, integrated (midpoint rule) into a drifting pose that starts at the identity.
struct OdometryOptions {
  double rate_hz = 50.0;
  double speed_scale_error_stddev = 0.01;  // Drawn once per run,
  double speed_scale = 0.0;                // unless this is > 0: the scale, fixed.
  double speed_noise_stddev_mps = 0.02;
  double yaw_rate_bias_stddev_radps = 0.003;  // Drawn once per run.
  double yaw_rate_noise_stddev_radps = 0.01;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

// Strapdown IMU on the base (x forward, z up): specific force = (dv/dt, v * yaw rate, g) plus a
// bias that starts at a random value and random-walks, plus white noise; gyro likewise.
struct ImuOptions {
  double rate_hz = 200.0;
  double gravity_mps2 = 9.81;
  double accel_noise_stddev_mps2 = 0.05;
  double gyro_noise_stddev_radps = 0.005;
  double accel_bias_stddev_mps2 = 0.05;
  double gyro_bias_stddev_radps = 0.003;
  double accel_bias_walk_mps2_per_sqrt_s = 0.001;
  double gyro_bias_walk_radps_per_sqrt_s = 0.0001;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

// Stateful (drift, bias walk): call Step with increasing stamps.
class OdometrySimulator {
 public:
  OdometrySimulator(const OdometryOptions& options, uint64_t seed);
  sensor::OdometryData Step(double stamp_s, const RobotState& truth, double* speed_mps,
                            double* yaw_rate_radps);

 private:
  OdometryOptions options_;
  std::mt19937_64 rng_;
  double speed_scale_;
  double yaw_rate_bias_radps_;
  bool started_ = false;
  double last_stamp_s_ = 0.0;
  double last_speed_mps_ = 0.0;
  double last_yaw_rate_radps_ = 0.0;
  common::Rigid2d pose_;
};

class ImuSimulator {
 public:
  ImuSimulator(const ImuOptions& options, uint64_t seed);
  sensor::ImuData Step(double stamp_s, const RobotState& truth);

 private:
  ImuOptions options_;
  std::mt19937_64 rng_;
  Eigen::Vector3d accel_bias_;
  Eigen::Vector3d gyro_bias_;
  bool started_ = false;
  double last_stamp_s_ = 0.0;
};

}  // namespace sim
}  // namespace fusemap

#endif  // FUSEMAP_SIM_ODOMETRY_IMU_SIMULATOR_H_
