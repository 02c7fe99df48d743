#include "fusemap/io/lcm_log.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <string>
#include <vector>

#include "fusemap/io/lcm_conversions.h"
#include "fusemap_lcm/odometry2d_t.hpp"

namespace fusemap {
namespace io {
namespace {

std::string TempPath(const std::string& name) {
  return testing::TempDir() + "/fusemap_io_" + std::to_string(getpid()) + "_" + name;
}

// Writes kNumEvents alternating scan and odometry messages; odometry x encodes the index.
constexpr int kNumEvents = 50;

void WriteTestLog(const std::string& path) {
  LcmLogWriter writer;
  std::string error;
  ASSERT_TRUE(writer.Open(path, &error)) << error;
  for (int i = 0; i < kNumEvents; ++i) {
    const int64_t utime = 1000000 + 100000 * i;
    if (i % 2 == 0) {
      sensor::LaserScan scan;
      scan.stamp_s = UtimeToStamp(utime);
      scan.angle_increment_rad = 0.1f;
      scan.range_max_m = 10.f;
      scan.ranges_m.assign(5, static_cast<float>(i));
      const std::vector<uint8_t> bytes = EncodeLaserScan(scan);
      ASSERT_TRUE(writer.Write("LIDAR", utime, bytes.data(), static_cast<int>(bytes.size())));
    } else {
      fusemap_lcm::odometry2d_t msg{};
      msg.utime = utime;
      msg.x = i;
      ASSERT_TRUE(writer.Write("ODOMETRY", utime, msg));  // the templated overload
    }
  }
  EXPECT_EQ(writer.num_written(), kNumEvents);
  writer.Close();
}

TEST(LcmLogTest, ReaderReturnsWhatWriterWrote) {
  const std::string path = TempPath("roundtrip.lcm");
  WriteTestLog(path);
  LcmLogReader reader;
  std::string error;
  ASSERT_TRUE(reader.Open(path, &error)) << error;
  LogEvent event;
  int count = 0;
  while (reader.Next(&event)) {
    EXPECT_EQ(event.utime, 1000000 + 100000 * count);
    if (count % 2 == 0) {
      EXPECT_EQ(event.channel, "LIDAR");
      sensor::LaserScan scan;
      ASSERT_TRUE(DecodeLaserScan(event.data.data(), static_cast<int>(event.data.size()),
                                  LidarChannelConfig(), &scan, &error))
          << error;
      EXPECT_EQ(scan.ranges_m.size(), 5u);
      EXPECT_EQ(scan.ranges_m[0], static_cast<float>(count));
    } else {
      EXPECT_EQ(event.channel, "ODOMETRY");
      sensor::OdometryData odom;
      ASSERT_TRUE(DecodeOdometry(event.data.data(), static_cast<int>(event.data.size()), &odom,
                                 &error))
          << error;
      EXPECT_DOUBLE_EQ(odom.pose.x(), count);
    }
    ++count;
  }
  EXPECT_EQ(count, kNumEvents);
  std::remove(path.c_str());
}

TEST(LcmLogTest, OpenFailsWithMessage) {
  LcmLogReader reader;
  std::string error;
  EXPECT_FALSE(reader.Open("/nonexistent/dir/x.lcm", &error));
  EXPECT_NE(error.find("/nonexistent/dir/x.lcm"), std::string::npos);
  LcmLogWriter writer;
  EXPECT_FALSE(writer.Open("/nonexistent/dir/x.lcm", &error));
  EXPECT_FALSE(writer.Write("X", 0, "a", 1));
}

// Issue 18, item 14: a directory opened "fine" and fusemap_offline then said it had no usable
// scans.
TEST(LcmLogTest, DirectoryIsNotALog) {
  LcmLogReader reader;
  std::string error;
  EXPECT_FALSE(reader.Open(::testing::TempDir(), &error));
  EXPECT_NE(error.find("is a directory"), std::string::npos) << error;
}

struct OdometryCounter {
  std::vector<double> xs;
};

// A plain function, not a member: GCC's -fsanitize=vptr flags LCM's member-handler trampoline
// (lcm-cpp-impl.hpp) even though the call is fine, as in daemon::LcmInput.
void CountOdometry(const lcm::ReceiveBuffer*, const std::string& channel,
                   const fusemap_lcm::odometry2d_t* msg, OdometryCounter* counter) {
  EXPECT_EQ(channel, "ODOMETRY");
  counter->xs.push_back(msg->x);
}

void CountRaw(const lcm::ReceiveBuffer*, const std::string&, int* count) { ++*count; }

// The same file replayed through LCM's own file:// provider, as lcm-logplayer would.
TEST(LcmLogTest, LcmFileProviderReplaysTheLog) {
  const std::string path = TempPath("provider.lcm");
  WriteTestLog(path);
  lcm::LCM lcm("file://" + path + "?speed=0");
  ASSERT_TRUE(lcm.good());
  OdometryCounter counter;
  int raw_count = 0;
  lcm.subscribeFunction("ODOMETRY", &CountOdometry, &counter);
  lcm.subscribeFunction(".*", &CountRaw, &raw_count);
  // handleTimeout returns 0 on timeout and < 0 once the log is exhausted.
  for (int i = 0; i < 10 * kNumEvents && lcm.handleTimeout(1000) > 0; ++i) {
  }
  EXPECT_EQ(raw_count, kNumEvents);
  ASSERT_EQ(counter.xs.size(), static_cast<size_t>(kNumEvents / 2));
  for (size_t k = 0; k < counter.xs.size(); ++k) EXPECT_DOUBLE_EQ(counter.xs[k], 2.0 * k + 1.0);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace io
}  // namespace fusemap
