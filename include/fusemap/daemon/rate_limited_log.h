#ifndef FUSEMAP_DAEMON_RATE_LIMITED_LOG_H_
#define FUSEMAP_DAEMON_RATE_LIMITED_LOG_H_

#include <functional>
#include <map>
#include <mutex>
#include <string>

namespace fusemap {
namespace daemon {

// Logs bad-input reports without flooding: per key (for example "LIDAR: truncated"), the first
// report is written at once, later ones at most once per `interval_s`, each such line saying how
// many were suppressed since. Time comes from `now_s` (seconds, any monotonic origin) so tests
// can drive it; the sink receives complete lines. Thread-safe.
class RateLimitedLog {
 public:
  using Clock = std::function<double()>;
  using Sink = std::function<void(const std::string& line)>;

  RateLimitedLog(double interval_s, Clock now_s, Sink sink);
  // Default clock: steady_clock; default sink: stderr with a "fusemapd: " prefix.
  explicit RateLimitedLog(double interval_s);

  // Returns true if a line was written.
  bool Report(const std::string& key, const std::string& message);
  int suppressed_total() const;

 private:
  struct KeyState {
    double last_written_s = 0.0;
    int suppressed = 0;
  };
  const double interval_s_;
  const Clock now_s_;
  const Sink sink_;
  mutable std::mutex mutex_;
  std::map<std::string, KeyState> keys_;  // guarded by mutex_
  int suppressed_total_ = 0;              // guarded by mutex_
};

}  // namespace daemon
}  // namespace fusemap

#endif  // FUSEMAP_DAEMON_RATE_LIMITED_LOG_H_
