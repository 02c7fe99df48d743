// Bounded random fuzzing of every decoder the daemon's intake uses: random bytes, truncations,
// bit flips and overwritten count fields of valid messages. The property: no crash, no hang,
// no huge allocation (ASan/valgrind-clean runs catch the rest), and valid messages still decode.
#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "fusemap/daemon/intake.h"
#include "fusemap/io/lcm_conversions.h"
#include "fusemap/io/rgbd_conversions.h"
#include "fusemap_lcm/planar_lidar_t.hpp"

namespace fusemap {
namespace daemon {
namespace {

constexpr int kIterationsPerSeed = 400;

using Decoder = std::function<bool(const std::vector<uint8_t>&)>;

struct Case {
  std::string name;
  std::vector<uint8_t> valid;
  Decoder decode;
};

sensor::LaserScan Scan() {
  sensor::LaserScan scan;
  scan.stamp_s = 1700000000.0;
  scan.angle_min_rad = -1.5f;
  scan.angle_increment_rad = 0.05f;
  scan.range_min_m = 0.1f;
  scan.range_max_m = 12.f;
  for (int i = 0; i < 60; ++i) scan.ranges_m.push_back(1.f + 0.1f * i);
  scan.intensities.assign(60, 100.f);
  return scan;
}

std::vector<uint8_t> PlanarLidar() {
  fusemap_lcm::planar_lidar_t msg;
  msg.utime = 1700000000000000;
  msg.nranges = 30;
  msg.ranges.assign(30, 2.5f);
  msg.nintensities = 0;
  msg.rad0 = -1.f;
  msg.radstep = 0.05f;
  std::vector<uint8_t> bytes(msg.getEncodedSize());
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

std::vector<uint8_t> Rgbd(const std::string& color, const std::string& depth) {
  sensor::RgbdFrame frame;
  frame.stamp_s = 1700000000.0;
  frame.color_intrinsics = {8, 6, 5.0, 5.0, 4.0, 3.0};
  frame.depth_intrinsics = frame.color_intrinsics;
  frame.color_rgb.assign(8 * 6 * 3, 0);
  for (size_t i = 0; i < frame.color_rgb.size(); ++i) frame.color_rgb[i] = static_cast<uint8_t>(i);
  frame.depth_mm.assign(8 * 6, 1500);
  io::RgbdEncodeOptions options;
  options.color_encoding = color;
  options.depth_encoding = depth;
  std::vector<uint8_t> bytes;
  std::string error;
  EXPECT_TRUE(io::EncodeRgbdFrame(frame, options, &bytes, &error)) << error;
  return bytes;
}

std::vector<Case> Cases() {
  const io::LidarChannelConfig lidar;
  std::vector<Case> cases;
  const auto laser = [lidar](const std::vector<uint8_t>& b) {
    sensor::LaserScan scan;
    std::string error;
    return io::DecodeLaserScan(b.data(), static_cast<int>(b.size()), lidar, &scan, &error);
  };
  cases.push_back({"laser_scan_t", io::EncodeLaserScan(Scan()), laser});
  cases.push_back({"planar_lidar_t", PlanarLidar(), laser});
  cases.push_back({"odometry2d_t", io::EncodeOdometry({1700000000.0, common::Rigid2d(1, 2, 0.3)}),
                   [](const std::vector<uint8_t>& b) {
                     sensor::OdometryData o;
                     std::string error;
                     return io::DecodeOdometry(b.data(), static_cast<int>(b.size()), &o, &error);
                   }});
  sensor::ImuData imu;
  imu.stamp_s = 1700000000.0;
  cases.push_back({"imu_t", io::EncodeImu(imu), [](const std::vector<uint8_t>& b) {
                     sensor::ImuData i;
                     std::string error;
                     return io::DecodeImu(b.data(), static_cast<int>(b.size()), &i, &error);
                   }});
  const Decoder rgbd = [](const std::vector<uint8_t>& b) {
    sensor::RgbdFrame f;
    std::string error;
    return io::DecodeRgbdFrame(b.data(), static_cast<int>(b.size()), &f, &error);
  };
  cases.push_back({"rgbd_frame_t raw", Rgbd("rgb8", "mono16"), rgbd});
  cases.push_back({"rgbd_frame_t compressed", Rgbd("jpeg", "png16"), rgbd});
  return cases;
}

std::vector<uint8_t> Mutate(const std::vector<uint8_t>& valid, std::mt19937& rng) {
  std::vector<uint8_t> b = valid;
  const auto pick = [&rng](size_t n) { return static_cast<size_t>(rng() % n); };
  switch (rng() % 5) {
    case 0:  // random bytes, random length (sometimes with the valid fingerprint)
      b.resize(pick(valid.size() * 2 + 1));
      for (auto& byte : b) byte = static_cast<uint8_t>(rng());
      if (b.size() >= 8 && rng() % 2 == 0) std::copy(valid.begin(), valid.begin() + 8, b.begin());
      break;
    case 1:  // truncation
      b.resize(pick(valid.size()));
      break;
    case 2:  // bit flips
      for (int i = 0, n = 1 + static_cast<int>(pick(8)); i < n; ++i) {
        b[pick(b.size())] ^= static_cast<uint8_t>(1u << pick(8));
      }
      break;
    case 3:  // a 4-byte field overwritten with an extreme value (counts, sizes)
      if (b.size() >= 12) {
        const size_t at = 8 + pick(b.size() - 11);
        const uint8_t v = rng() % 2 ? 0xff : 0x7f;
        for (size_t i = 0; i < 4; ++i) b[at + i] = i == 0 ? v : 0xff;
      }
      break;
    default:  // trailing garbage
      b.push_back(static_cast<uint8_t>(rng()));
      break;
  }
  return b;
}

TEST(DecoderFuzzTest, MutatedMessagesNeverCrashAndValidOnesDecode) {
  for (const Case& c : Cases()) {
    ASSERT_TRUE(c.decode(c.valid)) << c.name;
    std::mt19937 rng(7);
    int rejected = 0;
    for (int i = 0; i < kIterationsPerSeed; ++i) {
      if (!c.decode(Mutate(c.valid, rng))) ++rejected;
      if (i % 50 == 0) {
        ASSERT_TRUE(c.decode(c.valid)) << c.name;
      }
    }
    // Most mutations must be caught (flips inside float payloads may stay valid).
    EXPECT_GT(rejected, kIterationsPerSeed / 3) << c.name;
  }
}

TEST(DecoderFuzzTest, IntakeSurvivesGarbageOnEveryChannel) {
  DaemonOptions options;
  options.sensor_queue_size = 8;
  int lines = 0;
  RateLimitedLog log(1e9, [] { return 0.0; }, [&lines](const std::string&) { ++lines; });
  Intake intake(io::SlamConfig(), options, OverflowPolicy::kDropOldest, &log,
                [] { return 1700000001.0; });
  intake.set_decode_rgbd(true);
  const std::vector<std::string> channels = {"LIDAR", "LIDAR", "ODOMETRY", "IMU", "RGBD", "RGBD"};
  const std::vector<Case> cases = Cases();
  std::mt19937 rng(11);
  for (int i = 0; i < kIterationsPerSeed; ++i) {
    const size_t k = rng() % cases.size();
    const auto bytes = Mutate(cases[k].valid, rng);
    intake.OnMessage(channels[k], bytes.data(), static_cast<int>(bytes.size()));
    intake.sensor_queue().PopUntil(std::chrono::steady_clock::now());
    intake.rgbd_queue().PopUntil(std::chrono::steady_clock::now());
  }
  int64_t malformed = 0;
  for (int c = 0; c < kNumInputChannels; ++c) {
    malformed += intake.counters(static_cast<InputChannel>(c)).malformed;
  }
  EXPECT_GT(malformed, kIterationsPerSeed / 3);
  // One line per kind of problem, however many messages: the log is rate-limited.
  EXPECT_LT(lines, 60);
}

}  // namespace
}  // namespace daemon
}  // namespace fusemap
