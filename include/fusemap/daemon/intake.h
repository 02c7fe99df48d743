#ifndef FUSEMAP_DAEMON_INTAKE_H_
#define FUSEMAP_DAEMON_INTAKE_H_

#include <array>
#include <atomic>
#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "fusemap/daemon/bounded_queue.h"
#include "fusemap/daemon/daemon_options.h"
#include "fusemap/daemon/health.h"
#include "fusemap/daemon/rate_limited_log.h"
#include "fusemap/io/rgbd_conversions.h"
#include "fusemap/io/slam_config.h"
#include "fusemap/sensor/rgbd_frame.h"
#include "fusemap/sensor/sensor_types.h"
#include "fusemap/sensor/stamp_gate.h"

namespace fusemap {
namespace daemon {

// Input channels by index (health reports them in this order).
enum InputChannel { kLidarChannel = 0, kOdometryChannel, kImuChannel, kRgbdChannel, kNumInputChannels };

// A decoded, validated laser/odometry/IMU message. They share one queue, so local SLAM sees them
// in arrival order, as the offline runner sees a log in file order.
struct SensorMessage {
  InputChannel channel = kLidarChannel;
  std::chrono::steady_clock::time_point received;
  std::variant<sensor::LaserScan, sensor::OdometryData, sensor::ImuData> data;
  // The first message queued on a new time base (sensor::StampFilter's time reset): the SLAM
  // thread calls SlamSession::OnTimeReset before it, in order with the data.
  bool after_time_reset = false;
};

// An RGB-D frame as the handler thread queues it: checked, with its images still compressed
// (`frame` has no pixels yet); Intake::DecodeImages, on the RGB-D thread, fills them in.
struct RgbdMessage {
  std::chrono::steady_clock::time_point received;
  sensor::RgbdFrame frame;
  io::RgbdImageData images;
};

// The edge between the wire and the SLAM threads: decodes and validates raw LCM messages and
// enqueues them. Bad messages (decoder rejects, NaN-ridden scans, absurd values, oversized
// payloads, stamps too far in the future, absurd or going backwards on their channel) are
// counted per channel as malformed, reported through the rate-limited log and dropped.
// Stamp order is sensor::StampFilter's (one policy with fusemap_offline): a stamp that jumps far
// ahead is held (counted as malformed meanwhile) until the channel's next message shows whether
// it was one outlier (dropped) or a new time base (released, uncounted); a plausible backwards
// jump of the laser (a looping lcm-logplayer, a clock set back) is a time reset: from then on
// every channel's stamps are shifted by one offset chosen so that the reset scan lands
// kTimeResetGapS after the previous scan, and published stamps are in that clock. After
// --resume, data stamped at or before the checkpoint is skipped and counted as such.
// OnMessage must be called from one thread at a time (the LCM handler thread); the queues and
// counters may be read from any thread.
class Intake {
 public:
  using WallClock = std::function<double()>;  // seconds since the UNIX epoch

  Intake(const io::SlamConfig& slam, const DaemonOptions& options, OverflowPolicy policy,
         RateLimitedLog* log, WallClock wall_clock_s = nullptr);
  Intake(const Intake&) = delete;
  Intake& operator=(const Intake&) = delete;

  // Returns true if the message was queued; false if the channel is not an input, the message
  // was malformed, or the queues are closed.
  bool OnMessage(const std::string& channel, const void* data, int size);

  // RGB-D frames are decoded only when someone consumes them (JPEG/PNG decoding is costly);
  // otherwise they are counted as received and ignored.
  void set_decode_rgbd(bool decode) { decode_rgbd_ = decode; }
  // Decodes a queued RGB-D message's images into message->frame (the costly part, kept off the
  // handler thread so that a large frame cannot stall the other channels). False, counted as
  // malformed and logged, if the image data does not decode to what its header declared.
  // Callable from the thread that pops rgbd_queue(), concurrently with OnMessage.
  bool DecodeImages(RgbdMessage* message);
  // Stops intake: queued items can still be popped (drain), new ones are refused.
  void Close();
  // Before any message (--resume): data of `channel` stamped at or before `stamp_s` is already
  // in the restored state and is skipped (counted as skipped) until the channel passes it.
  void SetResumePoint(InputChannel channel, double stamp_s) {
    stamp_gate_.filter().SetResumePoint(channel, stamp_s);
  }
  // Number of time resets so far.
  int64_t time_resets() const { return time_resets_; }
  static constexpr double kTimeResetGapS = sensor::StampFilter::kTimeResetGapS;

  BoundedQueue<SensorMessage>& sensor_queue() { return sensor_queue_; }
  BoundedQueue<RgbdMessage>& rgbd_queue() { return rgbd_queue_; }
  const ChannelCounters& counters(InputChannel channel) const { return counters_[channel]; }
  // Configured input channel names by InputChannel index (empty = not subscribed).
  const std::array<std::string, kNumInputChannels>& channel_names() const { return names_; }
  // Health rows: per channel counters and the depth of the queue it feeds.
  std::vector<HealthReport::Channel> ChannelHealth() const;

 private:
  bool Reject(InputChannel channel, const std::string& kind, const std::string& why);
  // A decoded message on its way to its queue: the stamp gate holds either kind.
  using AnyMessage = std::variant<SensorMessage, RgbdMessage>;
  // Future check of a decoded message's raw stamp, then the stamp gate; queues what it lets
  // through (a held message it releases first, re-stamped). Returns whether `message` was
  // queued.
  bool Admit(InputChannel channel, AnyMessage message);
  bool Enqueue(InputChannel channel, AnyMessage message);

  const io::SlamConfig slam_;
  const DaemonOptions options_;
  RateLimitedLog* const log_;
  const WallClock wall_clock_s_;
  std::array<std::string, kNumInputChannels> names_;
  std::array<ChannelCounters, kNumInputChannels> counters_;
  sensor::StampGate<AnyMessage> stamp_gate_;  // handler thread only
  std::atomic<int64_t> time_resets_{0};
  // A time reset the next queued sensor message carries (handler thread only).
  bool time_reset_pending_ = false;
  bool decode_rgbd_ = false;
  BoundedQueue<SensorMessage> sensor_queue_;
  BoundedQueue<RgbdMessage> rgbd_queue_;
};

}  // namespace daemon
}  // namespace fusemap

#endif  // FUSEMAP_DAEMON_INTAKE_H_
