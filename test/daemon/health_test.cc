#include "fusemap/daemon/health.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

namespace fusemap {
namespace daemon {
namespace {

TEST(HealthTest, PercentileNearestRank) {
  std::vector<double> values;
  for (int i = 100; i >= 1; --i) values.push_back(i);
  EXPECT_DOUBLE_EQ(Percentile(values, 0.5), 51.0);  // rank round(0.5 * 99) = 50 -> 51
  EXPECT_DOUBLE_EQ(Percentile(values, 0.99), 99.0);
  EXPECT_DOUBLE_EQ(Percentile(values, 1.0), 100.0);
  EXPECT_DOUBLE_EQ(Percentile({}, 0.5), 0.0);
}

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

TEST(HealthTest, ResidentMemoryIsPlausible) {
  const int64_t rss = ResidentMemoryBytes();
  EXPECT_GT(rss, 100 * 1024);
  EXPECT_LT(rss, int64_t{64} << 30);
}

TEST(HealthTest, ReleaseFreeMemoryReturnsFreedHeapPages) {
#ifndef __GLIBC__
  GTEST_SKIP() << "only glibc keeps freed pages this way";
#endif
#ifdef __SANITIZE_ADDRESS__
  // ASan's allocator replaces glibc's: freed blocks sit in its quarantine, and malloc_trim
  // has no heap of glibc's to trim.
  GTEST_SKIP() << "under AddressSanitizer the heap is ASan's, not glibc's";
#endif
  // 64 MB in small blocks (below the mmap threshold, so they come from the heap), all freed
  // but the last, which pins the top of the heap so that free() alone cannot shrink it.
  std::vector<std::unique_ptr<char[]>> blocks;
  for (int i = 0; i < 16384; ++i) {
    blocks.emplace_back(new char[4096]);
    for (int j = 0; j < 4096; j += 512) blocks.back()[j] = static_cast<char>(i + j);
  }
  for (size_t i = 0; i + 1 < blocks.size(); ++i) blocks[i].reset();
  const int64_t before = ResidentMemoryBytes();
  ReleaseFreeMemory();
  const int64_t after = ResidentMemoryBytes();
  EXPECT_LT(after, before - (32 << 20)) << before << " -> " << after;
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
