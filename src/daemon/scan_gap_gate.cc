#include "fusemap/daemon/scan_gap_gate.h"

#include <algorithm>

namespace fusemap {
namespace daemon {
namespace {

// Weight of a new interval in the running estimate: a few seconds of scans, so that one late
// scan does not move the gap.
constexpr double kIntervalWeight = 0.05;

std::chrono::steady_clock::duration Seconds(double s) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(s));
}

}  // namespace

void ScanGapGate::ScanDone(Clock::time_point now) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (last_scan_ != Clock::time_point{}) {
      const double dt_s = std::chrono::duration<double>(now - last_scan_).count();
      if (dt_s > 0.0 && dt_s <= options_.max_interval_s) {
        interval_s_ = interval_s_ == 0.0
                          ? dt_s
                          : (1.0 - kIntervalWeight) * interval_s_ + kIntervalWeight * dt_s;
      }
    }
    last_scan_ = now;
  }
  // Cheap when no one waits (no system call).
  scan_done_.notify_all();
}

void ScanGapGate::WaitForGap() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    const Clock::time_point until = WaitUntilLocked(Clock::now());
    if (until == Clock::time_point::min()) return;
    scan_done_.wait_until(lock, until);
    // Woken by a scan (work may start now), or at the stall deadline (the next pass lets it).
  }
}

void ScanGapGate::Close() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
  }
  scan_done_.notify_all();
}

ScanGapGate::Clock::time_point ScanGapGate::WaitUntil(Clock::time_point now) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return WaitUntilLocked(now);
}

double ScanGapGate::interval_s() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return interval_s_;
}

ScanGapGate::Clock::time_point ScanGapGate::WaitUntilLocked(Clock::time_point now) const {
  if (closed_ || interval_s_ == 0.0) return Clock::time_point::min();
  const auto since = now - last_scan_;
  const auto stall = Seconds(std::max(options_.stall_intervals * interval_s_, interval_s_));
  if (since < Seconds(options_.fraction * interval_s_) || since >= stall) {
    return Clock::time_point::min();
  }
  return last_scan_ + stall;
}

}  // namespace daemon
}  // namespace fusemap
