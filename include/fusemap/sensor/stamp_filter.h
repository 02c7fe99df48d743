#ifndef FUSEMAP_SENSOR_STAMP_FILTER_H_
#define FUSEMAP_SENSOR_STAMP_FILTER_H_

#include <cstdint>
#include <string>
#include <vector>

#include "fusemap/common/option_checker.h"

namespace fusemap {
namespace sensor {

struct StampFilterOptions {
  // Stamps outside [min_stamp_s, max_stamp_s] (seconds since the UNIX epoch) are malformed:
  // no clock or log player produces them (utime -2^62, a garbage field).
  double min_stamp_s = 0.0;
  double max_stamp_s = 1e10;  // the year 2286
  // A stamp this much ahead of the newest accepted stamp of any channel is a suspect jump: the
  // message is held back until the channel's next message shows whether the time base really
  // moved (it follows the suspect) or the suspect was one outlier (it does not). 0 = never.
  double max_jump_s = 60.0;
  // A stamp on the reference channel (the laser) this much before that channel's previous one
  // is a time reset (a looping log player): a new time base instead of a drop. On another
  // channel it is held until the laser resets or the channel's next message, also on the new
  // clock, confirms it (a looping player may replay odometry before the first scan). 0 = never.
  double time_reset_threshold_s = 5.0;
  // A backwards jump larger than this is no log loop: held as a suspect like a jump ahead, and
  // a time reset only if the next message follows it.
  double max_time_reset_s = 30.0 * 86400.0;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

// Decides, per message stamp, whether a sensor stream's message is in order. Channels are
// small integers; channel `reference_channel` (the laser) resets the time base at once, the
// others only once confirmed (time_reset_threshold_s). All channels share one offset, added to
// every raw stamp after a reset, so that consumers see one monotonic clock, as if the data had
// paused for kTimeResetGapS after the newest stamp of any channel. A message stamped at or
// before its channel's resume point (SetResumePoint) is skipped until the channel's stream
// has passed that point, so a replay restarted from its beginning does not map data twice.
// One outlier costs one message: it is held, not accepted, so the messages after it are judged
// against the clock they agree with. Pure; not thread-safe.
class StampFilter {
 public:
  static constexpr double kTimeResetGapS = 1.0;

  enum class Verdict { kAccept, kHold, kReject, kSkip };
  // What happens to the channel's held message (from an earlier kHold), decided before the
  // current message: released (pass it on, at held_stamp_s, before the current message) or
  // dropped as an outlier.
  enum class Held { kNone, kRelease, kDrop };
  struct Decision {
    Verdict verdict = Verdict::kAccept;
    double stamp_s = 0.0;  // kAccept: the re-based stamp to use
    std::string kind;      // kReject, kHold: short kind for counters and logs
    std::string reason;    // kReject, kHold, kSkip and time resets: one line
    bool time_reset = false;
    Held held = Held::kNone;
    double held_stamp_s = 0.0;  // kRelease: the held message's re-based stamp
    std::string held_reason;    // kDrop
  };

  StampFilter(const StampFilterOptions& options, int num_channels, int reference_channel);

  Decision Check(int channel, double raw_stamp_s);
  // Before any message: data stamped at or before stamp_s on `channel` is already mapped.
  void SetResumePoint(int channel, double stamp_s);
  int64_t time_resets() const { return time_resets_; }
  double time_offset_s() const { return offset_s_; }

 private:
  struct Suspect {
    bool active = false;
    double raw_s = 0.0;
    // A backwards jump beyond max_time_reset_s (reference channel), or beyond
    // time_reset_threshold_s (other channels: a log loop seen before the laser's).
    bool backwards = false;
    int64_t time_resets = 0;  // time_resets_ when it was held
  };
  // The held suspect of `channel`, decided by the channel's next stamp `raw_s`.
  Held ResolveSuspect(int channel, double raw_s, double* held_stamp_s, std::string* held_reason,
                      std::string* reset_reason);
  // Holds the message at `raw_s` as the channel's suspect.
  Decision Hold(int channel, double raw_s, bool backwards, std::string reason);
  // The time-reset and order checks of a raw stamp with no suspect pending.
  Decision Judge(int channel, double raw_s);
  void Accept(int channel, double rebased_s);
  void Reset(int channel, double raw_s, std::string* reason);

  const StampFilterOptions options_;
  const int reference_channel_;
  std::vector<double> last_s_;         // re-based; -inf before the first message
  std::vector<double> resume_s_;       // raw; -inf without a resume point
  std::vector<Suspect> suspects_;
  double newest_s_;                    // the newest accepted re-based stamp of any channel
  double offset_s_ = 0.0;
  int64_t time_resets_ = 0;
};

}  // namespace sensor
}  // namespace fusemap

#endif  // FUSEMAP_SENSOR_STAMP_FILTER_H_
