#ifndef FUSEMAP_DAEMON_HEALTH_H_
#define FUSEMAP_DAEMON_HEALTH_H_

#include <atomic>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <vector>

#include "fusemap/io/health_report.h"

namespace fusemap {
namespace daemon {

// Counters of one input channel, bumped by the intake and the queues' drop callbacks and read
// by the publisher: lock-free because the LCM handler must never wait on the publisher.
struct ChannelCounters {
  std::atomic<int64_t> received{0};
  std::atomic<int64_t> dropped{0};
  std::atomic<int64_t> malformed{0};
  // Already in the restored checkpoint (--resume): neither mapped again nor malformed.
  std::atomic<int64_t> skipped{0};
};

// Scan-to-pose latencies over the most recent `window` scans (milliseconds). Thread-safe.
class LatencyWindow {
 public:
  explicit LatencyWindow(size_t window = 2000) : window_(window) {}
  void Add(double latency_ms);
  using Summary = io::LatencySummary;
  Summary Summarize() const;

 private:
  const size_t window_;
  mutable std::mutex mutex_;
  std::deque<double> samples_;  // guarded by mutex_
};


// The report the publisher sends as fusemap_lcm::health_t (defined in io, which encodes it).
using HealthReport = io::HealthReport;

// One line for logs: "nodes=.. submaps=.. LIDAR=rx/drop/bad ... p50=..ms p99=..ms rss=..MB",
// with "resume_skipped=N" (all channels) once anything was skipped after --resume.
std::string FormatHealth(const HealthReport& report);

}  // namespace daemon
}  // namespace fusemap

#endif  // FUSEMAP_DAEMON_HEALTH_H_
