#ifndef FUSEMAP_DAEMON_SCAN_GAP_GATE_H_
#define FUSEMAP_DAEMON_SCAN_GAP_GATE_H_

#include <chrono>
#include <condition_variable>
#include <mutex>

namespace fusemap {
namespace daemon {

// Lets work that may lag (the visual loop checker's) run in the gaps between scans. On two
// cores, a checker running beside the SLAM thread crowds the publisher and LCM threads onto
// the SLAM thread's core (issue 17: the scan->pose p99 with the checker on). The SLAM thread
// marks each scan done; WaitForGap returns while the time since that mark is under `fraction`
// of the usual scan interval (so that a piece of work started then mostly ends before the next
// scan), or at once when scans have stopped coming (no laser, end of a log), before the
// interval is known (two scans) or once the gate is closed.
// Thread-safe.
class ScanGapGate {
 public:
  using Clock = std::chrono::steady_clock;

  struct Options {
    double fraction = 0.4;  // of the scan interval, from a scan's end, in which work may start
    // Scans further apart than this are a stall, not the interval.
    double max_interval_s = 0.5;
    // With no scan for this many intervals, work runs freely.
    double stall_intervals = 3.0;
  };

  ScanGapGate() : ScanGapGate(Options{}) {}
  explicit ScanGapGate(const Options& options) : options_(options) {}

  // SLAM thread, as soon as it has processed a scan.
  void ScanDone(Clock::time_point now);
  // Blocks until work may start (see above).
  void WaitForGap();
  // Every wait returns at once from now on.
  void Close();

  // The decision, for a given time: Clock::time_point::min() if work may start at `now`, else
  // the latest time to wait for the next scan before running anyway.
  Clock::time_point WaitUntil(Clock::time_point now) const;
  double interval_s() const;

 private:
  Clock::time_point WaitUntilLocked(Clock::time_point now) const;

  const Options options_;
  mutable std::mutex mutex_;
  std::condition_variable scan_done_;
  Clock::time_point last_scan_{};  // guarded by mutex_
  double interval_s_ = 0.0;        // guarded by mutex_; 0: not known yet
  bool closed_ = false;            // guarded by mutex_
};

}  // namespace daemon
}  // namespace fusemap

#endif  // FUSEMAP_DAEMON_SCAN_GAP_GATE_H_
