#ifndef FUSEMAP_SENSOR_STAMP_GATE_H_
#define FUSEMAP_SENSOR_STAMP_GATE_H_

#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include "fusemap/sensor/stamp_filter.h"

namespace fusemap {
namespace sensor {

// A StampFilter that also keeps the messages it holds: a message whose stamp is a suspect jump
// waits here until its channel's next message shows whether the time base moved (the held
// message is released, re-stamped, to go on before the new one) or it was one outlier (it is
// dropped). fusemapd's intake and fusemap_offline both pass every decoded message through one,
// so a log gives the same messages to SLAM in either. Pure; not thread-safe.
template <typename Message>
class StampGate {
 public:
  // The message's stamp, as a reference: the gate re-bases it in place.
  using StampOf = std::function<double&(Message&)>;

  struct Result {
    StampFilter::Decision decision;
    // A held message the decision confirmed, re-stamped: it goes on before the offered one.
    std::optional<Message> released;
    // The offered message goes on now (re-stamped); otherwise it was held, rejected or skipped
    // (decision.verdict says which).
    bool pass = false;
  };

  StampGate(const StampFilterOptions& options, int num_channels, int reference_channel,
            StampOf stamp_of)
      : filter_(options, num_channels, reference_channel),
        stamp_of_(std::move(stamp_of)),
        held_(num_channels) {}

  // Judges `message` on `channel`; a message the filter holds is moved into the gate.
  Result Offer(int channel, Message& message) {
    Result result;
    result.decision = filter_.Check(channel, stamp_of_(message));
    std::optional<Message> held = std::move(held_[channel]);
    held_[channel].reset();
    if (result.decision.held == StampFilter::Held::kRelease && held) {
      stamp_of_(*held) = result.decision.held_stamp_s;
      result.released = std::move(held);
    }
    switch (result.decision.verdict) {
      case StampFilter::Verdict::kAccept:
        stamp_of_(message) = result.decision.stamp_s;
        result.pass = true;
        break;
      case StampFilter::Verdict::kHold:
        held_[channel] = std::move(message);
        break;
      case StampFilter::Verdict::kReject:
      case StampFilter::Verdict::kSkip:
        break;
    }
    return result;
  }

  // Messages still held: at the end of input, jumps nothing confirmed (dropped).
  int num_held() const {
    int n = 0;
    for (const auto& message : held_) n += message.has_value();
    return n;
  }
  StampFilter& filter() { return filter_; }
  const StampFilter& filter() const { return filter_; }

 private:
  StampFilter filter_;
  const StampOf stamp_of_;
  std::vector<std::optional<Message>> held_;  // by channel
};

}  // namespace sensor
}  // namespace fusemap

#endif  // FUSEMAP_SENSOR_STAMP_GATE_H_
