#include "fusemap/common/process_memory.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

namespace fusemap {
namespace common {
namespace {

TEST(ProcessMemoryTest, ResidentMemoryIsPlausible) {
  const int64_t rss = ResidentMemoryBytes();
  EXPECT_GT(rss, 100 * 1024);
  EXPECT_LT(rss, int64_t{64} << 30);
}

TEST(ProcessMemoryTest, ReleaseFreeMemoryReturnsFreedHeapPages) {
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

}  // namespace
}  // namespace common
}  // namespace fusemap
