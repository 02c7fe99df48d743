#ifndef FUSEMAP_IO_LCM_CONVERSIONS_H_
#define FUSEMAP_IO_LCM_CONVERSIONS_H_

#include <cstdint>
#include <string>
#include <vector>

#include "fusemap/common/option_checker.h"
#include "fusemap/sensor/sensor_types.h"

namespace fusemap {
namespace io {

// Scans with more beams than this are rejected as corrupt (no planar lidar comes close).
constexpr int kMaxLaserBeams = 100000;
// Finite values beyond these are no measurement but a corrupt field; taken in, they would grow
// the maps without bound (a scan 1e300 m away). Positions: 1000 km; angles: 1e6 rad (an
// unwrapped heading of 160,000 turns); speeds: 1 km/s, 1000 rad/s; acceleration: 1000 g.
constexpr double kMaxAbsPositionM = 1e6;
constexpr double kMaxAbsAngleRad = 1e6;
constexpr double kMaxAbsSpeedMps = 1e3;
constexpr double kMaxAbsAngularSpeedRadps = 1e3;
constexpr double kMaxAbsAccelerationMps2 = 1e4;
constexpr float kMaxLaserRangeM = 1e5f;

// What a lidar channel's configuration supplies that fusemap_lcm::planar_lidar_t (libbot2
// compatible) does not carry. laser_scan_t messages bring their own limits and frame.
struct LidarChannelConfig {
  std::string frame = "laser";
  float range_min_m = 0.f;
  float range_max_m = 30.f;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

struct LaserDecodeStats {
  // NaN or infinite ranges, replaced by range_max_m: "no return" under LaserScan's
  // [range_min_m, range_max_m) convention, yet finite so ray casting stays well defined.
  int nonfinite_ranges = 0;
};

// LCM utime (int64 microseconds) <-> seconds; rounding to the nearest microsecond.
int64_t StampToUtime(double stamp_s);
double UtimeToStamp(int64_t utime);

// Decodes the raw bytes of a fusemap_lcm::laser_scan_t or fusemap_lcm::planar_lidar_t (told
// apart by the 8-byte fingerprint that starts every LCM message). For planar_lidar_t, the frame
// and range limits come from `cfg`. Returns false with a reason in *error on truncated data,
// an unknown fingerprint, trailing bytes, non-finite angles or limits, more than kMaxLaserBeams
// beams, range_max beyond kMaxLaserRangeM, angles beyond kMaxAbsAngleRad, or an intensity
// count other than 0 or nranges. `stats` may be null.
bool DecodeLaserScan(const void* data, int size, const LidarChannelConfig& cfg,
                     sensor::LaserScan* out, std::string* error,
                     LaserDecodeStats* stats = nullptr);
// Encodes as fusemap_lcm::laser_scan_t (self-describing: frame and range limits included).
std::vector<uint8_t> EncodeLaserScan(const sensor::LaserScan& scan);

// fusemap_lcm::odometry2d_t. Velocities are not part of OdometryData; they are written as
// given and, when decoding, returned through the optional pointers. Non-finite or absurd
// values (beyond the kMaxAbs* bounds above) are refused.
bool DecodeOdometry(const void* data, int size, sensor::OdometryData* out, std::string* error,
                    double* linear_velocity_mps = nullptr,
                    double* angular_velocity_radps = nullptr);
std::vector<uint8_t> EncodeOdometry(const sensor::OdometryData& odometry,
                                    double linear_velocity_mps = 0.0,
                                    double angular_velocity_radps = 0.0);

// fusemap_lcm::imu_t. The optional orientation is not part of ImuData: ignored when decoding
// (but must be finite if has_orientation), written as absent when encoding. Non-finite or
// absurd rates and accelerations (beyond the kMaxAbs* bounds above) are refused.
bool DecodeImu(const void* data, int size, sensor::ImuData* out, std::string* error);
std::vector<uint8_t> EncodeImu(const sensor::ImuData& imu);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_LCM_CONVERSIONS_H_
