#include "fusemap/sim/odometry_imu_simulator.h"

#include <cmath>

#include "random.h"

namespace fusemap {
namespace sim {
namespace {

double Draw(std::mt19937_64* rng, double stddev) {
  return stddev > 0.0 ? std::normal_distribution<double>(0.0, stddev)(*rng) : 0.0;
}

}  // namespace

void OdometryOptions::Check(common::OptionChecker* check) const {
  check->Require(rate_hz > 0.0, "rate_hz", "must be > 0");
  check->Require(speed_scale_error_stddev >= 0.0, "speed_scale_error_stddev", "must be >= 0");
  check->Require(speed_scale >= 0.0, "speed_scale", "must be >= 0 (0: drawn)");
  check->Require(speed_noise_stddev_mps >= 0.0, "speed_noise_stddev_mps", "must be >= 0");
  check->Require(yaw_rate_bias_stddev_radps >= 0.0, "yaw_rate_bias_stddev_radps", "must be >= 0");
  check->Require(yaw_rate_noise_stddev_radps >= 0.0, "yaw_rate_noise_stddev_radps",
                 "must be >= 0");
}

bool OdometryOptions::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

void ImuOptions::Check(common::OptionChecker* check) const {
  check->Require(rate_hz > 0.0, "rate_hz", "must be > 0");
  check->Require(accel_noise_stddev_mps2 >= 0.0, "accel_noise_stddev_mps2", "must be >= 0");
  check->Require(gyro_noise_stddev_radps >= 0.0, "gyro_noise_stddev_radps", "must be >= 0");
  check->Require(accel_bias_stddev_mps2 >= 0.0, "accel_bias_stddev_mps2", "must be >= 0");
  check->Require(gyro_bias_stddev_radps >= 0.0, "gyro_bias_stddev_radps", "must be >= 0");
  check->Require(accel_bias_walk_mps2_per_sqrt_s >= 0.0, "accel_bias_walk_mps2_per_sqrt_s",
                 "must be >= 0");
  check->Require(gyro_bias_walk_radps_per_sqrt_s >= 0.0, "gyro_bias_walk_radps_per_sqrt_s",
                 "must be >= 0");
}

bool ImuOptions::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

OdometrySimulator::OdometrySimulator(const OdometryOptions& options, uint64_t seed)
    : options_(options), rng_(MakeRng(seed, NoiseStream::kOdometry, 0)) {
  // Drawn either way, so that a fixed scale leaves every later draw as it was.
  const double drawn_scale = 1.0 + Draw(&rng_, options_.speed_scale_error_stddev);
  speed_scale_ = options_.speed_scale > 0.0 ? options_.speed_scale : drawn_scale;
  yaw_rate_bias_radps_ = Draw(&rng_, options_.yaw_rate_bias_stddev_radps);
}

sensor::OdometryData OdometrySimulator::Step(double stamp_s, const RobotState& truth,
                                             double* speed_mps, double* yaw_rate_radps) {
  // A robot at rest reads exactly zero (encoders do not count while the wheels stand still).
  const bool moving = truth.speed_mps > 1e-6 || std::abs(truth.yaw_rate_radps) > 1e-6;
  const double speed_noise = Draw(&rng_, options_.speed_noise_stddev_mps);
  const double yaw_noise = Draw(&rng_, options_.yaw_rate_noise_stddev_radps);
  const double speed = moving ? speed_scale_ * truth.speed_mps + speed_noise : 0.0;
  const double yaw_rate =
      moving ? truth.yaw_rate_radps + yaw_rate_bias_radps_ + yaw_noise : 0.0;
  if (started_) {
    const double dt = stamp_s - last_stamp_s_;
    const double v = 0.5 * (speed + last_speed_mps_);
    const double w = 0.5 * (yaw_rate + last_yaw_rate_radps_);
    const double mid_heading = pose_.angle_rad() + 0.5 * w * dt;
    pose_ = common::Rigid2d(
        pose_.translation() + v * dt * Eigen::Vector2d(std::cos(mid_heading), std::sin(mid_heading)),
        pose_.angle_rad() + w * dt);
  }
  started_ = true;
  last_stamp_s_ = stamp_s;
  last_speed_mps_ = speed;
  last_yaw_rate_radps_ = yaw_rate;
  *speed_mps = speed;
  *yaw_rate_radps = yaw_rate;
  sensor::OdometryData data;
  data.stamp_s = stamp_s;
  data.pose = pose_;
  return data;
}

ImuSimulator::ImuSimulator(const ImuOptions& options, uint64_t seed)
    : options_(options), rng_(MakeRng(seed, NoiseStream::kImu, 0)) {
  for (int i = 0; i < 3; ++i) {
    accel_bias_[i] = Draw(&rng_, options_.accel_bias_stddev_mps2);
    gyro_bias_[i] = Draw(&rng_, options_.gyro_bias_stddev_radps);
  }
}

sensor::ImuData ImuSimulator::Step(double stamp_s, const RobotState& truth) {
  if (started_) {
    const double sqrt_dt = std::sqrt(std::max(0.0, stamp_s - last_stamp_s_));
    for (int i = 0; i < 3; ++i) {
      accel_bias_[i] += Draw(&rng_, options_.accel_bias_walk_mps2_per_sqrt_s * sqrt_dt);
      gyro_bias_[i] += Draw(&rng_, options_.gyro_bias_walk_radps_per_sqrt_s * sqrt_dt);
    }
  }
  started_ = true;
  last_stamp_s_ = stamp_s;
  sensor::ImuData imu;
  imu.stamp_s = stamp_s;
  const Eigen::Vector3d specific_force(truth.forward_accel_mps2,
                                       truth.speed_mps * truth.yaw_rate_radps,
                                       options_.gravity_mps2);
  const Eigen::Vector3d rate(0.0, 0.0, truth.yaw_rate_radps);
  for (int i = 0; i < 3; ++i) {
    imu.linear_acceleration_mps2[i] =
        specific_force[i] + accel_bias_[i] + Draw(&rng_, options_.accel_noise_stddev_mps2);
    imu.angular_velocity_radps[i] =
        rate[i] + gyro_bias_[i] + Draw(&rng_, options_.gyro_noise_stddev_radps);
  }
  return imu;
}

}  // namespace sim
}  // namespace fusemap
