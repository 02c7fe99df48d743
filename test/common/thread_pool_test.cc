#include "fusemap/common/thread_pool.h"

#include <gtest/gtest.h>

#include <atomic>

namespace fusemap {
namespace common {
namespace {

TEST(ThreadPoolTest, RunsEveryTaskBeforeWaitIdleReturns) {
  ThreadPool pool(2);
  std::atomic<int> sum{0};
  for (int i = 1; i <= 1000; ++i) pool.Schedule([&sum, i] { sum += i; });
  pool.WaitIdle();
  EXPECT_EQ(sum.load(), 500500);
}

TEST(ThreadPoolTest, TasksMayScheduleMoreTasks) {
  ThreadPool pool(2);
  std::atomic<int> count{0};
  for (int i = 0; i < 10; ++i) {
    pool.Schedule([&] {
      ++count;
      pool.Schedule([&] { ++count; });
    });
  }
  pool.WaitIdle();
  EXPECT_EQ(count.load(), 20);
}

TEST(ThreadPoolTest, DestructorDrainsPendingWork) {
  std::atomic<int> count{0};
  {
    ThreadPool pool(1);
    for (int i = 0; i < 100; ++i) pool.Schedule([&] { ++count; });
  }
  EXPECT_EQ(count.load(), 100);
}

TEST(InlineExecutorTest, RunsImmediately) {
  InlineExecutor executor;
  int x = 0;
  executor.Schedule([&] { x = 3; });
  EXPECT_EQ(x, 3);
}

}  // namespace
}  // namespace common
}  // namespace fusemap
