#ifndef FUSEMAP_DAEMON_INTAKE_H_
#define FUSEMAP_DAEMON_INTAKE_H_

#include <array>
#include <atomic>
#include <chrono>
#include <functional>
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
};

// An RGB-D frame as the handler thread queues it: checked, with its images still compressed
// (`frame` has no pixels yet); Intake::DecodeImages, on the RGB-D thread, fills them in.
struct RgbdMessage {
  std::chrono::steady_clock::time_point received;
  sensor::RgbdFrame frame;
  io::RgbdImageData images;
};

// The edge between the wire and the SLAM threads: decodes and validates raw LCM messages and
// enqueues them. Bad messages (decoder rejects, NaN-ridden scans, oversized payloads, stamps too
// far in the future or going backwards on their channel) are counted per channel, reported
// through the rate-limited log and dropped.
// Time resets: a laser stamp more than options.time_reset_threshold_s before the previous one
// (a looping lcm-logplayer, a robot whose clock was set back) is not dropped but starts a new
// time base: from then on every channel's stamps are shifted by one offset chosen so that the
// reset scan lands kTimeResetGapS after the previous scan. The SLAM thus sees one monotonic
// clock, as if the data had paused for kTimeResetGapS; published stamps are in that clock. OnMessage must be called from one thread at a time
// (the LCM handler thread); the queues and counters may be read from any thread.
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
  // Before any message: nothing stamped before `stamp_s` is accepted (after --resume, the
  // restored map's last time), except laser stamps older by more than the time-reset
  // threshold, which start a new time base after it.
  void SeedStamps(double stamp_s) { last_stamp_s_.fill(stamp_s); }
  // Number of time resets so far, and the current offset added to incoming stamps.
  int64_t time_resets() const { return time_resets_; }
  static constexpr double kTimeResetGapS = 1.0;

  BoundedQueue<SensorMessage>& sensor_queue() { return sensor_queue_; }
  BoundedQueue<RgbdMessage>& rgbd_queue() { return rgbd_queue_; }
  const ChannelCounters& counters(InputChannel channel) const { return counters_[channel]; }
  // Configured input channel names by InputChannel index (empty = not subscribed).
  const std::array<std::string, kNumInputChannels>& channel_names() const { return names_; }
  // Health rows: per channel counters and the depth of the queue it feeds.
  std::vector<HealthReport::Channel> ChannelHealth() const;

 private:
  bool Reject(InputChannel channel, const std::string& kind, const std::string& why);
  // Future check of a decoded message's raw stamp, then time-reset detection (laser) and the
  // backwards check of the re-based stamp, which replaces *stamp_s.
  bool CheckStamp(InputChannel channel, double* stamp_s);
  bool Enqueue(InputChannel channel, SensorMessage message);

  const io::SlamConfig slam_;
  const DaemonOptions options_;
  RateLimitedLog* const log_;
  const WallClock wall_clock_s_;
  std::array<std::string, kNumInputChannels> names_;
  std::array<ChannelCounters, kNumInputChannels> counters_;
  std::array<double, kNumInputChannels> last_stamp_s_;  // re-based; handler thread only
  double time_offset_s_ = 0.0;                            // handler thread only
  std::atomic<int64_t> time_resets_{0};
  bool decode_rgbd_ = false;
  BoundedQueue<SensorMessage> sensor_queue_;
  BoundedQueue<RgbdMessage> rgbd_queue_;
};

}  // namespace daemon
}  // namespace fusemap

#endif  // FUSEMAP_DAEMON_INTAKE_H_
