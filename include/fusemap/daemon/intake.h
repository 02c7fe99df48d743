#ifndef FUSEMAP_DAEMON_INTAKE_H_
#define FUSEMAP_DAEMON_INTAKE_H_

#include <array>
#include <chrono>
#include <functional>
#include <string>
#include <variant>
#include <vector>

#include "fusemap/daemon/bounded_queue.h"
#include "fusemap/daemon/daemon_options.h"
#include "fusemap/daemon/health.h"
#include "fusemap/daemon/rate_limited_log.h"
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

struct RgbdMessage {
  std::chrono::steady_clock::time_point received;
  sensor::RgbdFrame frame;
};

// The edge between the wire and the SLAM threads: decodes and validates raw LCM messages and
// enqueues them. Bad messages (decoder rejects, NaN-ridden scans, oversized payloads, stamps too
// far in the future or going backwards on their channel) are counted per channel, reported
// through the rate-limited log and dropped. OnMessage must be called from one thread at a time
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
  // Stops intake: queued items can still be popped (drain), new ones are refused.
  void Close();

  BoundedQueue<SensorMessage>& sensor_queue() { return sensor_queue_; }
  BoundedQueue<RgbdMessage>& rgbd_queue() { return rgbd_queue_; }
  const ChannelCounters& counters(InputChannel channel) const { return counters_[channel]; }
  // Configured input channel names by InputChannel index (empty = not subscribed).
  const std::array<std::string, kNumInputChannels>& channel_names() const { return names_; }
  // Health rows: per channel counters and the depth of the queue it feeds.
  std::vector<HealthReport::Channel> ChannelHealth() const;

 private:
  bool Reject(InputChannel channel, const std::string& kind, const std::string& why);
  // Future and backwards checks of a decoded message's stamp.
  bool CheckStamp(InputChannel channel, double stamp_s);
  bool Enqueue(InputChannel channel, SensorMessage message);

  const io::SlamConfig slam_;
  const DaemonOptions options_;
  RateLimitedLog* const log_;
  const WallClock wall_clock_s_;
  std::array<std::string, kNumInputChannels> names_;
  std::array<ChannelCounters, kNumInputChannels> counters_;
  std::array<double, kNumInputChannels> last_stamp_s_;  // handler thread only
  bool decode_rgbd_ = false;
  BoundedQueue<SensorMessage> sensor_queue_;
  BoundedQueue<RgbdMessage> rgbd_queue_;
};

}  // namespace daemon
}  // namespace fusemap

#endif  // FUSEMAP_DAEMON_INTAKE_H_
