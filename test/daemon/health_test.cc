#include "fusemap/daemon/health.h"

#include <gtest/gtest.h>

#include <vector>

namespace fusemap {
namespace daemon {
namespace {

TEST(HealthTest, LatencyWindowKeepsOnlyRecentSamples) {
  LatencyWindow window(10);
  for (int i = 0; i < 10; ++i) window.Add(1000.0);  // pushed out below
  for (int i = 1; i <= 10; ++i) window.Add(i);
  const auto summary = window.Summarize();
  EXPECT_EQ(summary.count, 10u);
  EXPECT_DOUBLE_EQ(summary.max_ms, 10.0);
  EXPECT_DOUBLE_EQ(summary.median_ms, 6.0);
  EXPECT_DOUBLE_EQ(summary.p99_ms, 10.0);
}

TEST(HealthTest, FormatNamesChannelsAndCounts) {
  HealthReport report;
  report.nodes = 12;
  report.channels.push_back({"LIDAR", 100, 3, 2, 5});
  const std::string line = FormatHealth(report);
  EXPECT_NE(line.find("nodes=12"), std::string::npos) << line;
  EXPECT_NE(line.find("LIDAR=100/3/2/q5"), std::string::npos) << line;
}

}  // namespace
}  // namespace daemon
}  // namespace fusemap
