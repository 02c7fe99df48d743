#include "fusemap/daemon/rate_limited_log.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace fusemap {
namespace daemon {
namespace {

TEST(RateLimitedLogTest, FirstReportWrittenThenAtMostOncePerInterval) {
  double now_s = 0.0;
  std::vector<std::string> lines;
  RateLimitedLog log(10.0, [&now_s] { return now_s; },
                     [&lines](const std::string& line) { lines.push_back(line); });
  EXPECT_TRUE(log.Report("LIDAR: truncated", "a"));
  now_s = 1.0;
  EXPECT_FALSE(log.Report("LIDAR: truncated", "b"));
  EXPECT_FALSE(log.Report("LIDAR: truncated", "c"));
  // Another kind is not held back by the first.
  EXPECT_TRUE(log.Report("IMU: truncated", "d"));
  now_s = 10.5;
  EXPECT_TRUE(log.Report("LIDAR: truncated", "e"));
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], "LIDAR: truncated: a");
  EXPECT_EQ(lines[1], "IMU: truncated: d");
  EXPECT_EQ(lines[2], "LIDAR: truncated: e (2 more like it suppressed)");
  EXPECT_EQ(log.suppressed_total(), 2);
}

}  // namespace
}  // namespace daemon
}  // namespace fusemap
