#include "fusemap/io/lcm_conversions.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "fusemap_lcm/laser_scan_t.hpp"
#include "fusemap_lcm/planar_lidar_t.hpp"

namespace fusemap {
namespace io {
namespace {

sensor::LaserScan MakeScan() {
  sensor::LaserScan scan;
  scan.stamp_s = 12.345678;
  scan.frame = "laser";
  scan.angle_min_rad = -1.5f;
  scan.angle_increment_rad = 0.01f;
  scan.range_min_m = 0.05f;
  scan.range_max_m = 30.f;
  scan.ranges_m = {1.f, 2.5f, 29.f, 30.f};
  scan.intensities = {10.f, 20.f, 30.f, 40.f};
  return scan;
}

template <class Msg>
std::vector<uint8_t> Bytes(const Msg& msg) {
  std::vector<uint8_t> bytes(msg.getEncodedSize());
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

bool Decode(const std::vector<uint8_t>& bytes, sensor::LaserScan* scan, std::string* error,
            LaserDecodeStats* stats = nullptr) {
  return DecodeLaserScan(bytes.data(), static_cast<int>(bytes.size()), LidarChannelConfig(), scan,
                         error, stats);
}

TEST(LcmConversionsTest, UtimeRoundTrip) {
  EXPECT_EQ(StampToUtime(1.5), 1500000);
  EXPECT_EQ(StampToUtime(1134863807.658747), 1134863807658747);
  EXPECT_NEAR(UtimeToStamp(StampToUtime(2684.123456)), 2684.123456, 1e-6);
}

TEST(LcmConversionsTest, LaserScanRoundTrip) {
  const sensor::LaserScan in = MakeScan();
  const std::vector<uint8_t> bytes = EncodeLaserScan(in);
  sensor::LaserScan out;
  std::string error;
  ASSERT_TRUE(Decode(bytes, &out, &error)) << error;
  EXPECT_NEAR(out.stamp_s, in.stamp_s, 1e-6);
  EXPECT_EQ(out.frame, in.frame);
  EXPECT_EQ(out.angle_min_rad, in.angle_min_rad);
  EXPECT_EQ(out.angle_increment_rad, in.angle_increment_rad);
  EXPECT_EQ(out.range_min_m, in.range_min_m);
  EXPECT_EQ(out.range_max_m, in.range_max_m);
  EXPECT_EQ(out.ranges_m, in.ranges_m);
  EXPECT_EQ(out.intensities, in.intensities);
}

TEST(LcmConversionsTest, RejectsEveryTruncation) {
  const std::vector<uint8_t> bytes = EncodeLaserScan(MakeScan());
  for (size_t n = 0; n < bytes.size(); ++n) {
    const std::vector<uint8_t> cut(bytes.begin(), bytes.begin() + n);
    sensor::LaserScan out;
    std::string error;
    EXPECT_FALSE(Decode(cut, &out, &error)) << "accepted " << n << " bytes";
    EXPECT_FALSE(error.empty());
  }
  std::vector<uint8_t> longer = bytes;
  longer.push_back(0);
  sensor::LaserScan out;
  std::string error;
  EXPECT_FALSE(Decode(longer, &out, &error));
  EXPECT_NE(error.find("trailing"), std::string::npos) << error;
}

TEST(LcmConversionsTest, RejectsWrongFingerprint) {
  std::vector<uint8_t> bytes = EncodeLaserScan(MakeScan());
  bytes[3] ^= 0x40;
  sensor::LaserScan out;
  std::string error;
  EXPECT_FALSE(Decode(bytes, &out, &error));
  EXPECT_NE(error.find("fingerprint"), std::string::npos) << error;
  // An odometry message is well-formed LCM but not a scan.
  sensor::OdometryData odom;
  EXPECT_FALSE(Decode(EncodeOdometry(odom), &out, &error));
  // And a scan is not odometry.
  EXPECT_FALSE(DecodeOdometry(bytes.data(), static_cast<int>(bytes.size()), &odom, &error));
}

TEST(LcmConversionsTest, RejectsNonFiniteAnglesAndBadCounts) {
  fusemap_lcm::laser_scan_t msg;
  msg.utime = 1;
  msg.frame = "laser";
  msg.angle_min = std::numeric_limits<float>::quiet_NaN();
  msg.angle_increment = 0.1f;
  msg.range_min = 0.f;
  msg.range_max = 10.f;
  msg.nranges = 2;
  msg.ranges = {1.f, 2.f};
  msg.nintensities = 0;
  sensor::LaserScan out;
  std::string error;
  EXPECT_FALSE(Decode(Bytes(msg), &out, &error));
  msg.angle_min = 0.f;
  msg.angle_increment = std::numeric_limits<float>::infinity();
  EXPECT_FALSE(Decode(Bytes(msg), &out, &error));
  msg.angle_increment = 0.1f;
  ASSERT_TRUE(Decode(Bytes(msg), &out, &error)) << error;
  msg.nintensities = 1;
  msg.intensities = {5.f};
  EXPECT_FALSE(Decode(Bytes(msg), &out, &error));
  EXPECT_NE(error.find("intensity"), std::string::npos) << error;
}

TEST(LcmConversionsTest, RejectsAbsurdAndNegativeBeamCounts) {
  fusemap_lcm::planar_lidar_t msg;
  msg.utime = 1;
  msg.nranges = 0;
  msg.nintensities = 0;
  msg.rad0 = 0.f;
  msg.radstep = 0.f;
  std::vector<uint8_t> bytes = Bytes(msg);
  // nranges sits right after fingerprint and utime (big-endian int32 at offset 16).
  for (const uint32_t bad : {0xFFFFFFFFu, static_cast<uint32_t>(kMaxLaserBeams + 1)}) {
    for (int i = 0; i < 4; ++i) bytes[16 + i] = static_cast<uint8_t>(bad >> (24 - 8 * i));
    sensor::LaserScan out;
    std::string error;
    EXPECT_FALSE(Decode(bytes, &out, &error));
    EXPECT_NE(error.find("absurd"), std::string::npos) << error;
  }
}

TEST(LcmConversionsTest, NonFiniteRangesBecomeNoReturnAndAreCounted) {
  sensor::LaserScan in = MakeScan();
  in.ranges_m[1] = std::numeric_limits<float>::quiet_NaN();
  in.ranges_m[2] = std::numeric_limits<float>::infinity();
  sensor::LaserScan out;
  std::string error;
  LaserDecodeStats stats;
  ASSERT_TRUE(Decode(EncodeLaserScan(in), &out, &error, &stats)) << error;
  EXPECT_EQ(stats.nonfinite_ranges, 2);
  EXPECT_EQ(out.ranges_m[1], in.range_max_m);
  EXPECT_EQ(out.ranges_m[2], in.range_max_m);
  EXPECT_EQ(out.ranges_m[0], 1.f);
}

TEST(LcmConversionsTest, PlanarLidarTakesLimitsFromConfig) {
  fusemap_lcm::planar_lidar_t msg;
  msg.utime = 2000000;
  msg.nranges = 2;
  msg.ranges = {1.f, 2.f};
  msg.nintensities = 0;
  msg.rad0 = -1.f;
  msg.radstep = 0.5f;
  const std::vector<uint8_t> bytes = Bytes(msg);
  LidarChannelConfig cfg;
  cfg.frame = "rear";
  cfg.range_min_m = 0.2f;
  cfg.range_max_m = 8.f;
  sensor::LaserScan out;
  std::string error;
  ASSERT_TRUE(DecodeLaserScan(bytes.data(), static_cast<int>(bytes.size()), cfg, &out, &error));
  EXPECT_EQ(out.frame, "rear");
  EXPECT_EQ(out.range_min_m, 0.2f);
  EXPECT_EQ(out.range_max_m, 8.f);
  EXPECT_DOUBLE_EQ(out.stamp_s, 2.0);
  cfg.range_max_m = 0.f;  // an unconfigured channel cannot interpret planar_lidar_t
  EXPECT_FALSE(DecodeLaserScan(bytes.data(), static_cast<int>(bytes.size()), cfg, &out, &error));
}

TEST(LcmConversionsTest, OdometryRoundTripAndValidation) {
  sensor::OdometryData in;
  in.stamp_s = 3.25;
  in.pose = common::Rigid2d(1.0, -2.0, 3.0);
  std::vector<uint8_t> bytes = EncodeOdometry(in, 0.5, -0.25);
  sensor::OdometryData out;
  double v = 0.0, w = 0.0;
  std::string error;
  ASSERT_TRUE(DecodeOdometry(bytes.data(), static_cast<int>(bytes.size()), &out, &error, &v, &w));
  EXPECT_DOUBLE_EQ(out.stamp_s, 3.25);
  EXPECT_NEAR(out.pose.x(), 1.0, 1e-12);
  EXPECT_NEAR(out.pose.y(), -2.0, 1e-12);
  EXPECT_NEAR(out.pose.angle_rad(), 3.0, 1e-12);
  EXPECT_DOUBLE_EQ(v, 0.5);
  EXPECT_DOUBLE_EQ(w, -0.25);
  EXPECT_FALSE(DecodeOdometry(bytes.data(), static_cast<int>(bytes.size()) - 1, &out, &error));
  in.pose = common::Rigid2d(std::nan(""), 0.0, 0.0);
  bytes = EncodeOdometry(in);
  EXPECT_FALSE(DecodeOdometry(bytes.data(), static_cast<int>(bytes.size()), &out, &error));
}

TEST(LcmConversionsTest, ImuRoundTripAndValidation) {
  sensor::ImuData in;
  in.stamp_s = 7.5;
  in.linear_acceleration_mps2 = Eigen::Vector3d(0.1, -0.2, 9.81);
  in.angular_velocity_radps = Eigen::Vector3d(0.01, 0.02, -0.3);
  std::vector<uint8_t> bytes = EncodeImu(in);
  sensor::ImuData out;
  std::string error;
  ASSERT_TRUE(DecodeImu(bytes.data(), static_cast<int>(bytes.size()), &out, &error)) << error;
  EXPECT_DOUBLE_EQ(out.stamp_s, 7.5);
  EXPECT_TRUE(out.linear_acceleration_mps2.isApprox(in.linear_acceleration_mps2, 1e-15));
  EXPECT_TRUE(out.angular_velocity_radps.isApprox(in.angular_velocity_radps, 1e-15));
  EXPECT_FALSE(DecodeImu(bytes.data(), 10, &out, &error));
  in.angular_velocity_radps.x() = std::numeric_limits<double>::infinity();
  bytes = EncodeImu(in);
  EXPECT_FALSE(DecodeImu(bytes.data(), static_cast<int>(bytes.size()), &out, &error));
}

}  // namespace
}  // namespace io
}  // namespace fusemap
