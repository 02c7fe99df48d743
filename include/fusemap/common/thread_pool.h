#ifndef FUSEMAP_COMMON_THREAD_POOL_H_
#define FUSEMAP_COMMON_THREAD_POOL_H_

#include <semaphore.h>

#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace fusemap {
namespace common {

// Where algorithm libraries hand off work they can do in parallel (loop-closure searches,
// background optimisation). Libraries only see this interface; the program that owns the
// threads decides how many there are. InlineExecutor runs work at once on the caller's
// thread, which keeps runs bit-for-bit reproducible.
class Executor {
 public:
  virtual ~Executor() = default;
  virtual void Schedule(std::function<void()> task) = 0;
  // As Schedule, but ahead of every task still waiting: for upkeep (freeing memory, the
  // optimisation and the trimming it runs) that must not queue behind a backlog of searches.
  // Executors without a queue run it as Schedule does.
  virtual void ScheduleFirst(std::function<void()> task) { Schedule(std::move(task)); }
  // Blocks until every task scheduled so far has finished.
  virtual void WaitIdle() = 0;
};

class InlineExecutor : public Executor {
 public:
  void Schedule(std::function<void()> task) override { task(); }
  void WaitIdle() override {}
};

// Fixed-size pool; tasks run in FIFO order (ScheduleFirst's at the front) on whichever worker
// is free. `on_worker_start`, if given, runs first on each worker's own thread (fusemapd lowers
// the workers' priority there, so that background searches never take the CPU from pose
// publication).
// Schedule does not wait for a worker to get a CPU (only for the queue's lock, held for a push or
// a pop): the workers are woken through a semaphore, not a condition variable, whose signal in
// glibc can wait for a previously woken worker to get a CPU (__condvar_quiesce_and_switch_g1).
// fusemapd's SLAM thread schedules searches for every node at real-time priority while the
// workers run at low priority: that wait held scans for ~3 ms (issue 17, the scan->pose p99).
class ThreadPool : public Executor {
 public:
  explicit ThreadPool(int num_threads, std::function<void()> on_worker_start = {});
  ~ThreadPool() override;
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  void Schedule(std::function<void()> task) override;
  void ScheduleFirst(std::function<void()> task) override;
  void WaitIdle() override;

 private:
  void Work();

  std::mutex mutex_;
  sem_t work_available_;  // one post per task, and one per worker to stop it
  std::condition_variable idle_;
  std::deque<std::function<void()>> tasks_;  // guarded by mutex_
  int running_ = 0;                          // guarded by mutex_
  std::vector<std::thread> workers_;
};

}  // namespace common
}  // namespace fusemap

#endif  // FUSEMAP_COMMON_THREAD_POOL_H_
