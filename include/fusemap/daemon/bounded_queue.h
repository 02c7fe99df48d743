#ifndef FUSEMAP_DAEMON_BOUNDED_QUEUE_H_
#define FUSEMAP_DAEMON_BOUNDED_QUEUE_H_

#include <cassert>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <utility>

namespace fusemap {
namespace daemon {

// What Push does when the queue is full.
enum class OverflowPolicy {
  // Live sensors: the producer (the LCM handler) must never block, and fresh data is worth more
  // than stale data, so the oldest item is discarded and counted.
  kDropOldest,
  // Log replay: there is no real-time source to keep up with, and dropping would make the
  // result depend on thread timing, so the producer waits for room instead.
  kBlock,
};

// A FIFO of at most `capacity` items shared by producers and one or more consumers. Invariant:
// size() <= capacity. After Close(), Push refuses new items, and Pop keeps returning the items
// already queued (drain) and then empty once the queue is empty, so consumers can finish.
template <typename T>
class BoundedQueue {
 public:
  // Called with each item discarded by kDropOldest, under the queue's lock (keep it cheap).
  using DropCallback = std::function<void(const T&)>;

  BoundedQueue(size_t capacity, OverflowPolicy policy, DropCallback on_drop = nullptr)
      : capacity_(capacity), policy_(policy), on_drop_(std::move(on_drop)) {
    assert(capacity_ > 0);
  }
  BoundedQueue(const BoundedQueue&) = delete;
  BoundedQueue& operator=(const BoundedQueue&) = delete;

  // False if the queue was closed (the item is discarded, not counted as dropped).
  bool Push(T item) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      if (policy_ == OverflowPolicy::kBlock) {
        not_full_.wait(lock, [this] { return closed_ || items_.size() < capacity_; });
      }
      if (closed_) return false;
      if (items_.size() >= capacity_) {
        if (on_drop_) on_drop_(items_.front());
        items_.pop_front();
        ++dropped_;
      }
      items_.push_back(std::move(item));
      ++pushed_;
    }
    // Woken with the lock still held, a consumer that preempts this thread finds the mutex
    // taken and sleeps again, and the item waits until the scheduler runs this thread once
    // more (fusemapd: a pose held up to ~2 ms behind its own wake-up, issue 17).
    not_empty_.notify_one();
    return true;
  }

  // Blocks until an item is available or the queue is closed and drained (then empty).
  std::optional<T> Pop() {
    std::optional<T> item;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      not_empty_.wait(lock, [this] { return closed_ || !items_.empty(); });
      item = PopLocked();
    }
    if (item) not_full_.notify_one();  // outside the lock, as in Push
    return item;
  }

  // Like Pop but gives up at `deadline` (returns empty; check closed_and_drained()).
  template <typename Clock, typename Duration>
  std::optional<T> PopUntil(const std::chrono::time_point<Clock, Duration>& deadline) {
    std::optional<T> item;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      not_empty_.wait_until(lock, deadline, [this] { return closed_ || !items_.empty(); });
      item = PopLocked();
    }
    if (item) not_full_.notify_one();
    return item;
  }

  // Wakes every waiter; see the class comment for what happens to queued items.
  void Close() {
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
    not_empty_.notify_all();
    not_full_.notify_all();
  }

  size_t size() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return items_.size();
  }
  bool closed_and_drained() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return closed_ && items_.empty();
  }
  int64_t dropped() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return dropped_;
  }
  int64_t pushed() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return pushed_;
  }
  size_t capacity() const { return capacity_; }
  OverflowPolicy policy() const { return policy_; }

 private:
  std::optional<T> PopLocked() {
    if (items_.empty()) return std::nullopt;
    std::optional<T> item(std::move(items_.front()));
    items_.pop_front();
    return item;
  }

  const size_t capacity_;
  const OverflowPolicy policy_;
  const DropCallback on_drop_;
  mutable std::mutex mutex_;
  std::condition_variable not_empty_;
  std::condition_variable not_full_;
  std::deque<T> items_;  // guarded by mutex_
  bool closed_ = false;  // guarded by mutex_
  int64_t dropped_ = 0;  // guarded by mutex_
  int64_t pushed_ = 0;   // guarded by mutex_
};

}  // namespace daemon
}  // namespace fusemap

#endif  // FUSEMAP_DAEMON_BOUNDED_QUEUE_H_
