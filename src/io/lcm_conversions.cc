#include "fusemap/io/lcm_conversions.h"

#include <cmath>
#include <cstdio>
#include <cstring>

#include "fusemap_lcm/imu_t.hpp"
#include "fusemap_lcm/laser_scan_t.hpp"
#include "fusemap_lcm/odometry2d_t.hpp"
#include "fusemap_lcm/planar_lidar_t.hpp"
#include "lcm_wire.h"

namespace fusemap {
namespace io {
namespace {

using lcm_wire::AllFinite;
using lcm_wire::DecodeFixed;
using lcm_wire::Encode;
using lcm_wire::WireCursor;

bool WithinBound(double value, double bound) { return std::abs(value) <= bound; }

bool CheckLaserScanLayout(const void* data, int size, std::string* error) {
  WireCursor cursor(data, size);
  int64_t word = 0;
  int32_t frame_len = 0, nranges = 0, nintensities = 0;
  if (!cursor.ReadInt64(&word) || !cursor.ReadInt64(&word) || !cursor.ReadInt32(&frame_len)) {
    return WireCursor::Fail("truncated laser_scan_t header", error);
  }
  if (frame_len < 1 || !cursor.Skip(frame_len)) {
    return WireCursor::Fail("bad frame string length " + std::to_string(frame_len), error);
  }
  if (!cursor.Skip(16)) return WireCursor::Fail("truncated laser_scan_t limits", error);
  if (!cursor.SkipFloatArray("nranges", &nranges, error)) return false;
  if (!cursor.SkipFloatArray("nintensities", &nintensities, error)) return false;
  return cursor.AtEnd(error);
}

bool CheckPlanarLidarLayout(const void* data, int size, std::string* error) {
  WireCursor cursor(data, size);
  int64_t word = 0;
  int32_t nranges = 0, nintensities = 0;
  if (!cursor.ReadInt64(&word) || !cursor.ReadInt64(&word)) {
    return WireCursor::Fail("truncated planar_lidar_t header", error);
  }
  if (!cursor.SkipFloatArray("nranges", &nranges, error)) return false;
  if (!cursor.SkipFloatArray("nintensities", &nintensities, error)) return false;
  if (!cursor.Skip(8)) return WireCursor::Fail("truncated planar_lidar_t angles", error);
  return cursor.AtEnd(error);
}

}  // namespace

void LidarChannelConfig::Check(common::OptionChecker* check) const {
  check->Require(std::isfinite(range_min_m) && range_min_m >= 0.f, "range_min_m",
                 "must be >= 0");
  check->Require(std::isfinite(range_max_m) && range_max_m > range_min_m, "range_max_m",
                 "must be > range_min_m");
}

bool LidarChannelConfig::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

int64_t StampToUtime(double stamp_s) { return std::llround(stamp_s * 1e6); }
double UtimeToStamp(int64_t utime) { return static_cast<double>(utime) * 1e-6; }

bool DecodeLaserScan(const void* data, int size, const LidarChannelConfig& cfg,
                     sensor::LaserScan* out, std::string* error, LaserDecodeStats* stats) {
  WireCursor cursor(data, size);
  int64_t hash = 0;
  if (!cursor.ReadInt64(&hash)) return WireCursor::Fail("truncated fingerprint", error);
  sensor::LaserScan scan;
  if (hash == fusemap_lcm::laser_scan_t::getHash()) {
    if (!CheckLaserScanLayout(data, size, error)) return false;
    fusemap_lcm::laser_scan_t msg;
    if (msg.decode(data, 0, size) != size) return WireCursor::Fail("decode failed", error);
    scan.stamp_s = UtimeToStamp(msg.utime);
    scan.frame = msg.frame;
    scan.angle_min_rad = msg.angle_min;
    scan.angle_increment_rad = msg.angle_increment;
    scan.range_min_m = msg.range_min;
    scan.range_max_m = msg.range_max;
    scan.ranges_m = std::move(msg.ranges);
    scan.intensities = std::move(msg.intensities);
  } else if (hash == fusemap_lcm::planar_lidar_t::getHash()) {
    if (!CheckPlanarLidarLayout(data, size, error)) return false;
    if (!cfg.IsValid(error)) return false;
    fusemap_lcm::planar_lidar_t msg;
    if (msg.decode(data, 0, size) != size) return WireCursor::Fail("decode failed", error);
    scan.stamp_s = UtimeToStamp(msg.utime);
    scan.frame = cfg.frame;
    scan.angle_min_rad = msg.rad0;
    scan.angle_increment_rad = msg.radstep;
    scan.range_min_m = cfg.range_min_m;
    scan.range_max_m = cfg.range_max_m;
    scan.ranges_m = std::move(msg.ranges);
    scan.intensities = std::move(msg.intensities);
  } else {
    return WireCursor::Fail("fingerprint is neither laser_scan_t nor planar_lidar_t", error);
  }
  if (!std::isfinite(scan.angle_min_rad) || !std::isfinite(scan.angle_increment_rad)) {
    return WireCursor::Fail("non-finite scan angles", error);
  }
  if (!WithinBound(scan.angle_min_rad, kMaxAbsAngleRad) ||
      !WithinBound(scan.angle_increment_rad, kMaxAbsAngleRad)) {
    return WireCursor::Fail("absurd scan angles", error);
  }
  if (!(std::isfinite(scan.range_min_m) && std::isfinite(scan.range_max_m) &&
        scan.range_min_m >= 0.f && scan.range_min_m < scan.range_max_m)) {
    return WireCursor::Fail("range limits must satisfy 0 <= range_min < range_max", error);
  }
  if (scan.range_max_m > kMaxLaserRangeM) {
    return WireCursor::Fail("absurd range_max " + std::to_string(scan.range_max_m) + " m", error);
  }
  if (!scan.intensities.empty() && scan.intensities.size() != scan.ranges_m.size()) {
    return WireCursor::Fail("intensity count " + std::to_string(scan.intensities.size()) +
                                " is neither 0 nor nranges " +
                                std::to_string(scan.ranges_m.size()),
                            error);
  }
  int nonfinite = 0;
  for (float& r : scan.ranges_m) {
    if (!std::isfinite(r)) {
      r = scan.range_max_m;
      ++nonfinite;
    }
  }
  if (stats != nullptr) stats->nonfinite_ranges += nonfinite;
  *out = std::move(scan);
  return true;
}

std::vector<uint8_t> EncodeLaserScan(const sensor::LaserScan& scan) {
  fusemap_lcm::laser_scan_t msg;
  msg.utime = StampToUtime(scan.stamp_s);
  msg.frame = scan.frame;
  msg.angle_min = scan.angle_min_rad;
  msg.angle_increment = scan.angle_increment_rad;
  msg.range_min = scan.range_min_m;
  msg.range_max = scan.range_max_m;
  msg.nranges = static_cast<int32_t>(scan.ranges_m.size());
  msg.ranges = scan.ranges_m;
  msg.nintensities = static_cast<int32_t>(scan.intensities.size());
  msg.intensities = scan.intensities;
  return Encode(msg);
}

bool DecodeOdometry(const void* data, int size, sensor::OdometryData* out, std::string* error,
                    double* linear_velocity_mps, double* angular_velocity_radps) {
  fusemap_lcm::odometry2d_t msg;
  if (!DecodeFixed(data, size, &msg, error)) return false;
  const double values[] = {msg.x, msg.y, msg.theta, msg.linear_velocity, msg.angular_velocity};
  if (!AllFinite(values, 5)) return WireCursor::Fail("non-finite odometry field", error);
  if (!WithinBound(msg.x, kMaxAbsPositionM) || !WithinBound(msg.y, kMaxAbsPositionM) ||
      !WithinBound(msg.theta, kMaxAbsAngleRad) ||
      !WithinBound(msg.linear_velocity, kMaxAbsSpeedMps) ||
      !WithinBound(msg.angular_velocity, kMaxAbsAngularSpeedRadps)) {
    char reason[200];
    std::snprintf(reason, sizeof(reason), "absurd odometry x=%g y=%g theta=%g v=%g w=%g", msg.x,
                  msg.y, msg.theta, msg.linear_velocity, msg.angular_velocity);
    return WireCursor::Fail(reason, error);
  }
  out->stamp_s = UtimeToStamp(msg.utime);
  out->pose = common::Rigid2d(msg.x, msg.y, msg.theta);
  if (linear_velocity_mps != nullptr) *linear_velocity_mps = msg.linear_velocity;
  if (angular_velocity_radps != nullptr) *angular_velocity_radps = msg.angular_velocity;
  return true;
}

std::vector<uint8_t> EncodeOdometry(const sensor::OdometryData& odometry,
                                    double linear_velocity_mps, double angular_velocity_radps) {
  fusemap_lcm::odometry2d_t msg;
  msg.utime = StampToUtime(odometry.stamp_s);
  msg.x = odometry.pose.x();
  msg.y = odometry.pose.y();
  msg.theta = odometry.pose.angle_rad();
  msg.linear_velocity = linear_velocity_mps;
  msg.angular_velocity = angular_velocity_radps;
  return Encode(msg);
}

bool DecodeImu(const void* data, int size, sensor::ImuData* out, std::string* error) {
  fusemap_lcm::imu_t msg;
  if (!DecodeFixed(data, size, &msg, error)) return false;
  if (!AllFinite(msg.linear_acceleration, 3) || !AllFinite(msg.angular_velocity, 3) ||
      (msg.has_orientation && !AllFinite(msg.orientation, 4))) {
    return WireCursor::Fail("non-finite imu field", error);
  }
  for (int i = 0; i < 3; ++i) {
    if (!WithinBound(msg.linear_acceleration[i], kMaxAbsAccelerationMps2) ||
        !WithinBound(msg.angular_velocity[i], kMaxAbsAngularSpeedRadps)) {
      return WireCursor::Fail("absurd imu acceleration or angular velocity", error);
    }
  }
  out->stamp_s = UtimeToStamp(msg.utime);
  out->linear_acceleration_mps2 = Eigen::Map<const Eigen::Vector3d>(msg.linear_acceleration);
  out->angular_velocity_radps = Eigen::Map<const Eigen::Vector3d>(msg.angular_velocity);
  return true;
}

std::vector<uint8_t> EncodeImu(const sensor::ImuData& imu) {
  fusemap_lcm::imu_t msg;
  msg.utime = StampToUtime(imu.stamp_s);
  for (int i = 0; i < 3; ++i) {
    msg.linear_acceleration[i] = imu.linear_acceleration_mps2[i];
    msg.angular_velocity[i] = imu.angular_velocity_radps[i];
  }
  msg.has_orientation = false;
  const double identity[4] = {1.0, 0.0, 0.0, 0.0};
  std::memcpy(msg.orientation, identity, sizeof(identity));
  return Encode(msg);
}

}  // namespace io
}  // namespace fusemap
