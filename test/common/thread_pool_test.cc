#include "fusemap/common/thread_pool.h"

#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <fstream>
#include <future>
#include <mutex>
#include <set>
#include <string>
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

// State letter of thread `tid` of this process ('S': asleep, 'R': running or runnable).
char ThreadState(pid_t tid) {
  std::ifstream stat("/proc/self/task/" + std::to_string(tid) + "/stat");
  std::string line;
  std::getline(stat, line);
  const size_t comm_end = line.rfind(')');
  return comm_end == std::string::npos || comm_end + 2 >= line.size() ? '?' : line[comm_end + 2];
}

bool PinThisThread(int cpu) {
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(cpu, &set);
  return pthread_setaffinity_np(pthread_self(), sizeof(set), &set) == 0;
}

// 0, or the error number.
int MakeThisThreadFifo(int priority) {
  sched_param param{};
  param.sched_priority = priority;
  return pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
}

long VoluntarySwitchesOfThisThread() {
  rusage usage{};
  getrusage(RUSAGE_THREAD, &usage);
  return usage.ru_nvcsw;
}

// fusemapd's SLAM thread (SCHED_FIFO) schedules loop-closure searches for every node on workers
// of low priority. Scheduling must never wait for a worker woken earlier to get a CPU: with a
// condition variable it did (glibc's signal waits for the woken waiters of the group it closes),
// and scans waited ~3 ms behind it (issue 17). Here the workers' CPU is held by a real-time
// spinner, so a woken worker cannot run while the caller schedules; the caller must not block.
TEST(ThreadPoolTest, ScheduleNeverWaitsForAWokenWorkerToRun) {
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  ASSERT_EQ(sched_getaffinity(0, sizeof(allowed), &allowed), 0);
  std::vector<int> cpus;
  for (int cpu = 0; cpu < CPU_SETSIZE && cpus.size() < 2; ++cpu) {
    if (CPU_ISSET(cpu, &allowed)) cpus.push_back(cpu);
  }
  if (cpus.size() < 2) GTEST_SKIP() << "needs two CPUs";
  const int caller_cpu = cpus[0];
  const int worker_cpu = cpus[1];

  struct Outcome {
    std::string skip;  // why the test could not run
    std::string error;
    long blocked_switches = -1;
  };
  std::atomic<bool> hog{true};
  std::atomic<bool> hogging{false};
  std::atomic<bool> spinner_gave_up{false};
  // Spins on the workers' CPU at real-time priority while `hog` is set (at most 5 s, so that a
  // blocked caller still ends: the test then fails on the counts below, not by hanging).
  const auto spin = [&] {
    PinThisThread(worker_cpu);
    MakeThisThreadFifo(1);
    hogging = true;
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (hog && std::chrono::steady_clock::now() < give_up) {
    }
    spinner_gave_up = hog.load();
  };

  // Made here, at normal priority: threads inherit their creator's policy.
  std::mutex tids_mutex;
  std::vector<pid_t> tids;
  std::atomic<int> done{0};
  ThreadPool pool(2, [&] {
    PinThisThread(worker_cpu);
    std::lock_guard<std::mutex> lock(tids_mutex);
    tids.push_back(static_cast<pid_t>(syscall(SYS_gettid)));
  });
  Outcome outcome;
  std::thread caller([&] {
    if (!PinThisThread(caller_cpu)) {
      outcome.skip = "cannot pin a thread to a CPU";
      return;
    }
    if (const int error = MakeThisThreadFifo(2)) {
      outcome.skip =
          std::string("SCHED_FIFO refused (needs root or CAP_SYS_NICE): ") + std::strerror(error);
      return;
    }
    // Until both workers are asleep waiting for work.
    const auto both_asleep = [&] {
      const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
      while (std::chrono::steady_clock::now() < deadline) {
        std::lock_guard<std::mutex> lock(tids_mutex);
        if (tids.size() == 2 && ThreadState(tids[0]) == 'S' && ThreadState(tids[1]) == 'S') {
          return true;
        }
      }
      return false;
    };
    if (!both_asleep()) {
      outcome.error = "the workers never went to sleep";
      return;
    }
    // One worker runs a task and goes back to waiting; the other has waited all along.
    pool.Schedule([&] { ++done; });
    pool.WaitIdle();
    if (!both_asleep()) {
      outcome.error = "the workers never went back to sleep";
      return;
    }
    // Started from this thread, the spinner inherits its CPU and priority until it moves.
    std::thread spinner(spin);
    while (!hogging) std::this_thread::yield();
    const long before = VoluntarySwitchesOfThisThread();
    for (int i = 0; i < 3; ++i) pool.Schedule([&] { ++done; });
    outcome.blocked_switches = VoluntarySwitchesOfThisThread() - before;
    hog = false;
    spinner.join();
    pool.WaitIdle();
  });
  caller.join();
  if (!outcome.skip.empty()) GTEST_SKIP() << outcome.skip;
  ASSERT_TRUE(outcome.error.empty()) << outcome.error;
  EXPECT_EQ(outcome.blocked_switches, 0) << "Schedule slept while no worker could run";
  EXPECT_FALSE(spinner_gave_up);
  EXPECT_EQ(done.load(), 4);
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
