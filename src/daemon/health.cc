#include "fusemap/daemon/health.h"

#include "fusemap/common/math.h"

#include <algorithm>
#include <cstdio>

namespace fusemap {
namespace daemon {

void LatencyWindow::Add(double latency_ms) {
  std::lock_guard<std::mutex> lock(mutex_);
  samples_.push_back(latency_ms);
  if (samples_.size() > window_) samples_.pop_front();
}

LatencyWindow::Summary LatencyWindow::Summarize() const {
  std::vector<double> values;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    values.assign(samples_.begin(), samples_.end());
  }
  Summary summary;
  summary.count = values.size();
  if (values.empty()) return summary;
  summary.max_ms = *std::max_element(values.begin(), values.end());
  summary.p99_ms = common::Percentile(values, 0.99);
  summary.median_ms = common::Percentile(std::move(values), 0.5);
  return summary;
}

std::string FormatHealth(const HealthReport& report) {
  char buffer[256];
  std::snprintf(buffer, sizeof(buffer),
                "up=%.0fs nodes=%d submaps=%d constraints=%d loops=%d opt=%d pending_searches=%d",
                report.uptime_s, report.nodes, report.submaps, report.constraints,
                report.loop_closures, report.optimizations, report.pending_searches);
  std::string line = buffer;
  int64_t skipped = 0;
  for (const auto& c : report.channels) {
    skipped += c.skipped;
    std::snprintf(buffer, sizeof(buffer), " %s=%lld/%lld/%lld/q%d", c.name.c_str(),
                  static_cast<long long>(c.received), static_cast<long long>(c.dropped),
                  static_cast<long long>(c.malformed), c.queue_depth);
    line += buffer;
  }
  std::snprintf(buffer, sizeof(buffer),
                " latency_p50=%.1fms p99=%.1fms rss=%.0fMB ckpt_fail=%d time_resets=%lld"
                " trimmed_submaps=%d trimmed_nodes=%d",
                report.latency.median_ms, report.latency.p99_ms, report.rss_bytes / 1048576.0,
                report.checkpoint_failures, static_cast<long long>(report.time_resets),
                report.trimmed_submaps, report.trimmed_nodes);
  line += buffer;
  const HealthReport::Visual& v = report.visual;
  if (v.keyframes > 0 || v.dropped_frames > 0) {
    std::snprintf(buffer, sizeof(buffer),
                  " visual_keyframes=%d candidates=%d verified=%d forced=%d overridden=%d"
                  " rejected=%d visual_q%d visual_dropped=%lld",
                  v.keyframes, v.candidates, v.verified, v.forced, v.overridden, v.rejected,
                  v.queue_depth, static_cast<long long>(v.dropped_frames));
    line += buffer;
  }
  if (skipped > 0) line += " resume_skipped=" + std::to_string(skipped);
  return line;
}

}  // namespace daemon
}  // namespace fusemap
