#ifndef FUSEMAP_IO_HEALTH_REPORT_H_
#define FUSEMAP_IO_HEALTH_REPORT_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace fusemap {
namespace io {

// Scan-to-pose latencies over a window of recent scans (milliseconds).
struct LatencySummary {
  double median_ms = 0.0;
  double p99_ms = 0.0;
  double max_ms = 0.0;
  size_t count = 0;
};

// One health report of the daemon: what fusemap_lcm::health_t carries, as plain values, plus
// what only its log line shows (skipped, trimmed_*). It lives in io because the health_t
// encoder (lcm_output_conversions.h) takes it; the daemon fills it.
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
  LatencySummary latency;
  int64_t rss_bytes = 0;
  // In the graph now: trimming (lifelong mapping) removes what newer submaps cover again.
  int nodes = 0;
  int submaps = 0;
  int constraints = 0;
  int trimmed_nodes = 0;
  int trimmed_submaps = 0;
  int loop_closures = 0;
  int optimizations = 0;
  int pending_searches = 0;  // loop-closure searches queued, not yet finished
  // Checkpoints or trajectory-archive appends that could not be written, and time resets of
  // the input (see Intake).
  int checkpoint_failures = 0;
  int64_t time_resets = 0;
  // The ORB visual loop checker (session::VisualStage; 0 when off).
  struct Visual {
    int keyframes = 0;
    int candidates = 0;
    int verified = 0;
    int forced = 0;
    int overridden = 0;
    int rejected = 0;
    int queue_depth = 0;
    int64_t dropped_frames = 0;
  };
  Visual visual;
};

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_HEALTH_REPORT_H_
