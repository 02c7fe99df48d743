#include "fusemap/common/thread_pool.h"

#include <cassert>
#include <cerrno>

namespace fusemap {
namespace common {

ThreadPool::ThreadPool(int num_threads, std::function<void()> on_worker_start) {
  assert(num_threads > 0);
  sem_init(&work_available_, /*pshared=*/0, 0);
  for (int i = 0; i < num_threads; ++i) {
    workers_.emplace_back([this, on_worker_start] {
      if (on_worker_start) on_worker_start();
      Work();
    });
  }
}

ThreadPool::~ThreadPool() {
  for (size_t i = 0; i < workers_.size(); ++i) sem_post(&work_available_);
  for (auto& worker : workers_) worker.join();
  sem_destroy(&work_available_);
}

void ThreadPool::Schedule(std::function<void()> task) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    tasks_.push_back(std::move(task));
  }
  sem_post(&work_available_);
}

void ThreadPool::ScheduleFirst(std::function<void()> task) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    tasks_.push_front(std::move(task));
  }
  sem_post(&work_available_);
}

void ThreadPool::WaitIdle() {
  std::unique_lock<std::mutex> lock(mutex_);
  idle_.wait(lock, [this] { return tasks_.empty() && running_ == 0; });
}

void ThreadPool::Work() {
  for (;;) {
    while (sem_wait(&work_available_) != 0 && errno == EINTR) {
    }
    std::function<void()> task;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      // Each post is a task or, once stopping, a worker's end; tasks go first so that nothing
      // scheduled is silently lost (a task's post is always taken after the task was queued,
      // so an empty queue here means a stop).
      if (tasks_.empty()) return;
      task = std::move(tasks_.front());
      tasks_.pop_front();
      ++running_;
    }
    task();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      --running_;
      if (tasks_.empty() && running_ == 0) idle_.notify_all();
    }
  }
}

}  // namespace common
}  // namespace fusemap
