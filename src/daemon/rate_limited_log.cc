#include "fusemap/daemon/rate_limited_log.h"

#include <chrono>
#include <cstdio>
#include <utility>

namespace fusemap {
namespace daemon {

RateLimitedLog::RateLimitedLog(double interval_s, Clock now_s, Sink sink)
    : interval_s_(interval_s), now_s_(std::move(now_s)), sink_(std::move(sink)) {}

RateLimitedLog::RateLimitedLog(double interval_s)
    : RateLimitedLog(
          interval_s,
          [] {
            return std::chrono::duration<double>(
                       std::chrono::steady_clock::now().time_since_epoch())
                .count();
          },
          [](const std::string& line) { std::fprintf(stderr, "fusemapd: %s\n", line.c_str()); }) {}

bool RateLimitedLog::Report(const std::string& key, const std::string& message) {
  std::string line;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const double now_s = now_s_();
    auto [it, inserted] = keys_.try_emplace(key);
    KeyState& state = it->second;
    if (!inserted && now_s - state.last_written_s < interval_s_) {
      ++state.suppressed;
      ++suppressed_total_;
      return false;
    }
    line = key + ": " + message;
    if (state.suppressed > 0) {
      line += " (" + std::to_string(state.suppressed) + " more like it suppressed)";
    }
    state.last_written_s = now_s;
    state.suppressed = 0;
  }
  sink_(line);
  return true;
}

int RateLimitedLog::suppressed_total() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return suppressed_total_;
}

}  // namespace daemon
}  // namespace fusemap
