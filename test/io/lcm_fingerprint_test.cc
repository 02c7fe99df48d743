#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "bot_core/planar_lidar_t.hpp"
#include "bot_core/pose_t.hpp"
#include "fusemap/io/lcm_conversions.h"
#include "fusemap_lcm/planar_lidar_t.hpp"
#include "fusemap_lcm/pose_t.hpp"

namespace fusemap {
namespace io {
namespace {

// The fingerprint hashes field names and types but not the package, so equal hashes mean
// libbot2 publishers and our subscribers interoperate on the wire.
TEST(LcmFingerprintTest, PlanarLidarMatchesLibbot2) {
  EXPECT_EQ(fusemap_lcm::planar_lidar_t::getHash(), bot_core::planar_lidar_t::getHash());
}

TEST(LcmFingerprintTest, PoseMatchesLibbot2) {
  EXPECT_EQ(fusemap_lcm::pose_t::getHash(), bot_core::pose_t::getHash());
}

TEST(LcmFingerprintTest, Libbot2PlanarLidarDecodesAsLaserScan) {
  bot_core::planar_lidar_t msg;
  msg.utime = 1500000;
  msg.ranges = {1.f, 2.f, 3.f};
  msg.nranges = 3;
  msg.nintensities = 0;
  msg.rad0 = -0.5f;
  msg.radstep = 0.25f;
  std::vector<uint8_t> bytes(msg.getEncodedSize());
  ASSERT_EQ(msg.encode(bytes.data(), 0, static_cast<int>(bytes.size())),
            static_cast<int>(bytes.size()));

  LidarChannelConfig cfg;
  cfg.frame = "front_laser";
  cfg.range_min_m = 0.1f;
  cfg.range_max_m = 20.f;
  sensor::LaserScan scan;
  std::string error;
  ASSERT_TRUE(DecodeLaserScan(bytes.data(), static_cast<int>(bytes.size()), cfg, &scan, &error))
      << error;
  EXPECT_DOUBLE_EQ(scan.stamp_s, 1.5);
  EXPECT_EQ(scan.frame, "front_laser");
  EXPECT_FLOAT_EQ(scan.angle_min_rad, -0.5f);
  EXPECT_FLOAT_EQ(scan.angle_increment_rad, 0.25f);
  EXPECT_FLOAT_EQ(scan.range_max_m, 20.f);
  EXPECT_EQ(scan.ranges_m, std::vector<float>({1.f, 2.f, 3.f}));
}

}  // namespace
}  // namespace io
}  // namespace fusemap
