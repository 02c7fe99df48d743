#ifndef FUSEMAP_DAEMON_HEALTH_H_
#define FUSEMAP_DAEMON_HEALTH_H_

#include <atomic>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <vector>

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
  struct Summary {
    double median_ms = 0.0;
    double p99_ms = 0.0;
    double max_ms = 0.0;
    size_t count = 0;
  };
  Summary Summarize() const;

 private:
  const size_t window_;
  mutable std::mutex mutex_;
  std::deque<double> samples_;  // guarded by mutex_
};

// Nearest-rank percentile (q in [0, 1]) of `values`; 0 when empty.
double Percentile(std::vector<double> values, double q);

// Resident set size of this process from /proc/self/statm, or 0 where that is unavailable.
int64_t ResidentMemoryBytes();

// Returns free heap pages to the system (glibc's malloc_trim; a no-op elsewhere).
void ReleaseFreeMemory();

// One health report: what fusemap_lcm::health_t carries, as plain values.
struct HealthReport {
  double uptime_s = 0.0;
  struct Channel {
    std::string name;
    int64_t received = 0;
    int64_t dropped = 0;
    int64_t malformed = 0;
    int queue_depth = 0;
    int64_t skipped = 0;  // after --resume: already in the checkpoint
  };
  std::vector<Channel> channels;
  LatencyWindow::Summary latency;
  int64_t rss_bytes = 0;
  // In the graph now: trimming (lifelong mapping) removes what newer submaps cover again.
  int nodes = 0;
  int submaps = 0;
  int constraints = 0;
  int trimmed_nodes = 0;
  int trimmed_submaps = 0;
  int loop_closures = 0;
  int optimizations = 0;
  // Checkpoints or trajectory-archive appends that could not be written, and time resets of
  // the input (see Intake).
  int checkpoint_failures = 0;
  int64_t time_resets = 0;
};

// One line for logs: "nodes=.. submaps=.. LIDAR=rx/drop/bad ... p50=..ms p99=..ms rss=..MB",
// with "resume_skipped=N" (all channels) once anything was skipped after --resume.
std::string FormatHealth(const HealthReport& report);

}  // namespace daemon
}  // namespace fusemap

#endif  // FUSEMAP_DAEMON_HEALTH_H_
