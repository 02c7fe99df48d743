#include "fusemap/common/thread_pool.h"

#include <gtest/gtest.h>

#include <atomic>
#include <future>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

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

TEST(ThreadPoolTest, WorkerStartHookRunsOnEachWorkerBeforeItsFirstTask) {
  std::mutex mutex;
  std::set<std::thread::id> started;
  int tasks_on_unstarted_threads = 0;
  int tasks = 0;
  {
    ThreadPool pool(3, [&] {
      std::lock_guard<std::mutex> lock(mutex);
      started.insert(std::this_thread::get_id());
    });
    for (int i = 0; i < 200; ++i) {
      pool.Schedule([&] {
        std::lock_guard<std::mutex> lock(mutex);
        ++tasks;
        tasks_on_unstarted_threads += started.count(std::this_thread::get_id()) == 0;
      });
    }
    pool.WaitIdle();
  }
  EXPECT_EQ(tasks, 200);
  EXPECT_EQ(tasks_on_unstarted_threads, 0);
  // Once per worker, on the worker's own thread.
  EXPECT_EQ(started.size(), 3u);
  EXPECT_EQ(started.count(std::this_thread::get_id()), 0u);
}

TEST(ThreadPoolTest, ScheduleFirstRunsAheadOfWaitingTasks) {
  ThreadPool pool(1);
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::promise<void> started;
  // The one worker is held inside the first task while the others queue up.
  pool.Schedule([&started, released] {
    started.set_value();
    released.wait();
  });
  started.get_future().wait();
  std::mutex mutex;
  std::vector<int> order;
  const auto record = [&mutex, &order](int id) {
    return [&mutex, &order, id] {
      std::lock_guard<std::mutex> lock(mutex);
      order.push_back(id);
    };
  };
  pool.Schedule(record(1));
  pool.Schedule(record(2));
  pool.ScheduleFirst(record(3));
  pool.ScheduleFirst(record(4));
  release.set_value();
  pool.WaitIdle();
  EXPECT_EQ(order, (std::vector<int>{4, 3, 1, 2}));
}

TEST(InlineExecutorTest, RunsImmediately) {
  InlineExecutor executor;
  int x = 0;
  executor.Schedule([&] { x = 3; });
  EXPECT_EQ(x, 3);
  executor.ScheduleFirst([&] { x = 4; });
  EXPECT_EQ(x, 4);
}

}  // namespace
}  // namespace common
}  // namespace fusemap
