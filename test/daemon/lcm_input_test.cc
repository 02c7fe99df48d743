#include "fusemap/daemon/lcm_input.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <string>
#include <unistd.h>
#include <vector>

#include "fusemap/io/lcm_conversions.h"
#include "fusemap/io/lcm_log.h"

namespace fusemap {
namespace daemon {
namespace {

constexpr double kNowS = 1700000100.0;

std::string TempLogPath(const std::string& name) {
  return ::testing::TempDir() + "/lcm_input_test_" + std::to_string(::getpid()) + "_" + name;
}

TEST(LcmInputTest, UrlKindAndPolicy) {
  EXPECT_TRUE(IsLogUrl("file:///tmp/x.lcm?speed=0"));
  EXPECT_FALSE(IsLogUrl("udpm://239.255.76.67:7667"));
  EXPECT_EQ(PolicyForUrl("file:///tmp/x.lcm"), OverflowPolicy::kBlock);
  EXPECT_EQ(PolicyForUrl("memq://"), OverflowPolicy::kDropOldest);
}

TEST(LcmInputTest, OnlyAnUnpacedLogArrivesUnpaced) {
  EXPECT_TRUE(ArrivesPaced("udpm://239.255.76.67:7667?ttl=0"));
  EXPECT_TRUE(ArrivesPaced("memq://"));
  EXPECT_TRUE(ArrivesPaced("file:///tmp/x.lcm"));
  EXPECT_TRUE(ArrivesPaced("file:///tmp/x.lcm?speed=1"));
  EXPECT_TRUE(ArrivesPaced("file:///tmp/x.lcm?mode=r&speed=0.5"));
  EXPECT_FALSE(ArrivesPaced("file:///tmp/x.lcm?speed=0"));
  EXPECT_FALSE(ArrivesPaced("file:///tmp/x.lcm?mode=r&speed=0"));
  EXPECT_FALSE(ArrivesPaced("file:///tmp/x.lcm?speed=0.0&start_timestamp=5"));
}

TEST(LcmInputTest, MissingLogIsReportedNotCrashed) {
  LcmInput input;
  std::string error;
  EXPECT_FALSE(input.Open("file://" + TempLogPath("missing.lcm") + "?speed=0", &error));
  EXPECT_NE(error.find("is the log file readable?"), std::string::npos) << error;
}

// Every message of a file:// log on a subscribed channel reaches the intake, through LCM's C
// callback into LcmInput. This call once aborted every UBSan build (GCC's -fsanitize=vptr
// miscompiles the member-function-pointer call in lcm-cpp-impl.hpp; see lcm_input.cc).
TEST(LcmInputTest, LogMessagesReachTheIntake) {
  const std::string path = TempLogPath("replay.lcm");
  {
    io::LcmLogWriter writer;
    std::string error;
    ASSERT_TRUE(writer.Open(path, &error)) << error;
    const std::vector<uint8_t> odometry = io::EncodeOdometry({kNowS - 2.0, common::Rigid2d()});
    ASSERT_TRUE(writer.Write("ODOMETRY", 1, odometry.data(), static_cast<int>(odometry.size())));
    sensor::LaserScan scan;
    scan.stamp_s = kNowS - 1.9;
    scan.angle_min_rad = -1.f;
    scan.angle_increment_rad = 0.02f;
    scan.range_min_m = 0.1f;
    scan.range_max_m = 10.f;
    scan.ranges_m.assign(100, 3.f);
    const std::vector<uint8_t> laser = io::EncodeLaserScan(scan);
    ASSERT_TRUE(writer.Write("LIDAR", 2, laser.data(), static_cast<int>(laser.size())));
    ASSERT_TRUE(writer.Write("UNSUBSCRIBED", 3, laser.data(), static_cast<int>(laser.size())));
  }
  const std::string url = "file://" + path + "?speed=0";
  RateLimitedLog log(0.0, [] { return 0.0; }, [](const std::string&) {});
  Intake intake(io::SlamConfig(), DaemonOptions(), PolicyForUrl(url), &log, [] { return kNowS; });
  LcmInput input;
  std::string error;
  ASSERT_TRUE(input.Open(url, &error)) << error;
  EXPECT_EQ(input.publish_handle(), nullptr);
  input.Subscribe(&intake);
  std::atomic<bool> stop{false};
  EXPECT_EQ(input.Run(stop, 10), LcmInput::End::kEndOfLog);
  EXPECT_EQ(intake.counters(kOdometryChannel).received, 1);
  EXPECT_EQ(intake.counters(kLidarChannel).received, 1);
  ASSERT_EQ(intake.sensor_queue().size(), 2u);
  EXPECT_EQ(intake.sensor_queue().Pop()->channel, kOdometryChannel);
  EXPECT_EQ(intake.sensor_queue().Pop()->channel, kLidarChannel);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace daemon
}  // namespace fusemap
