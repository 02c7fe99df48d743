#include "fusemap/daemon/intake.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "fusemap/io/lcm_conversions.h"
#include "fusemap/io/rgbd_conversions.h"

namespace fusemap {
namespace daemon {
namespace {

double& StampOf(std::variant<SensorMessage, RgbdMessage>& message) {
  if (auto* rgbd = std::get_if<RgbdMessage>(&message)) return rgbd->frame.stamp_s;
  return std::visit([](auto& data) -> double& { return data.stamp_s; },
                    std::get<SensorMessage>(message).data);
}

double SystemClockSeconds() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace

Intake::Intake(const io::SlamConfig& slam, const DaemonOptions& options, OverflowPolicy policy,
               RateLimitedLog* log, WallClock wall_clock_s)
    : slam_(slam),
      options_(options),
      log_(log),
      wall_clock_s_(wall_clock_s ? std::move(wall_clock_s) : WallClock(SystemClockSeconds)),
      names_{slam.channels.lidar, slam.channels.odometry, slam.channels.imu, slam.channels.rgbd},
      stamp_gate_(options.stamp_filter(), kNumInputChannels, kLidarChannel, StampOf),
      sensor_queue_(options.sensor_queue_size, policy,
                    [this](const SensorMessage& m) { ++counters_[m.channel].dropped; }),
      rgbd_queue_(options.rgbd_queue_size, policy,
                  [this](const RgbdMessage&) { ++counters_[kRgbdChannel].dropped; }) {}

bool Intake::Reject(InputChannel channel, const std::string& kind, const std::string& why) {
  ++counters_[channel].malformed;
  if (log_ != nullptr) log_->Report(names_[channel] + ": " + kind, why);
  return false;
}

bool Intake::Admit(InputChannel channel, AnyMessage message) {
  const double now_s = wall_clock_s_();
  const double stamp_s = StampOf(message);
  if (stamp_s > now_s + options_.max_future_s) {
    char buffer[160];
    std::snprintf(buffer, sizeof(buffer), "stamp %.6f is %.1f s ahead of the clock; dropped",
                  stamp_s, stamp_s - now_s);
    return Reject(channel, "timestamp from the future", buffer);
  }
  using Verdict = sensor::StampFilter::Verdict;
  auto passed = stamp_gate_.Offer(channel, message);
  const sensor::StampFilter::Decision& decision = passed.decision;
  if (decision.time_reset) {
    ++time_resets_;
    time_reset_pending_ = true;
    if (log_ != nullptr) log_->Report(names_[channel] + ": time reset", decision.reason);
  }
  if (passed.released) {
    // Counted as malformed while held; the new time base is confirmed.
    --counters_[channel].malformed;
    Enqueue(channel, std::move(*passed.released));
  } else if (decision.held == sensor::StampFilter::Held::kDrop && log_ != nullptr) {
    log_->Report(names_[channel] + ": timestamp jump", decision.held_reason);
  }
  if (passed.pass) return Enqueue(channel, std::move(message));
  switch (decision.verdict) {
    case Verdict::kSkip:
      ++counters_[channel].skipped;
      return false;
    case Verdict::kHold:
      Reject(channel, decision.kind, decision.reason);
      return false;
    case Verdict::kAccept:
    case Verdict::kReject:
      break;
  }
  return Reject(channel, decision.kind, decision.reason);
}

bool Intake::Enqueue(InputChannel channel, AnyMessage message) {
  if (auto* rgbd = std::get_if<RgbdMessage>(&message)) return rgbd_queue_.Push(std::move(*rgbd));
  SensorMessage& sensor_message = std::get<SensorMessage>(message);
  sensor_message.channel = channel;
  sensor_message.after_time_reset = time_reset_pending_;
  time_reset_pending_ = false;
  return sensor_queue_.Push(std::move(sensor_message));
}

bool Intake::OnMessage(const std::string& channel, const void* data, int size) {
  const auto received = std::chrono::steady_clock::now();
  int index = -1;
  for (int i = 0; i < kNumInputChannels; ++i) {
    if (!names_[i].empty() && names_[i] == channel) index = i;
  }
  if (index < 0) return false;
  const InputChannel input = static_cast<InputChannel>(index);
  ++counters_[input].received;
  if (size < 0 || size > options_.max_message_bytes) {
    return Reject(input, "oversized message",
                  std::to_string(size) + " bytes (limit " +
                      std::to_string(options_.max_message_bytes) + "); dropped");
  }
  std::string error;
  SensorMessage message;
  message.received = received;
  switch (input) {
    case kLidarChannel: {
      sensor::LaserScan scan;
      io::LaserDecodeStats stats;
      if (!io::DecodeLaserScan(data, size, slam_.lidar, &scan, &error, &stats)) {
        return Reject(input, "undecodable scan", error);
      }
      if (scan.ranges_m.empty() || stats.nonfinite_ranges > options_.max_nonfinite_range_fraction *
                                                                 scan.ranges_m.size()) {
        return Reject(input, "scan without usable ranges",
                      std::to_string(stats.nonfinite_ranges) + " of " +
                          std::to_string(scan.ranges_m.size()) + " ranges are NaN/inf; dropped");
      }
      message.data = std::move(scan);
      return Admit(input, std::move(message));
    }
    case kOdometryChannel: {
      sensor::OdometryData odometry;
      if (!io::DecodeOdometry(data, size, &odometry, &error)) {
        return Reject(input, "undecodable odometry", error);
      }
      message.data = odometry;
      return Admit(input, std::move(message));
    }
    case kImuChannel: {
      sensor::ImuData imu;
      if (!io::DecodeImu(data, size, &imu, &error)) return Reject(input, "undecodable IMU", error);
      message.data = imu;
      return Admit(input, std::move(message));
    }
    case kRgbdChannel: {
      if (!decode_rgbd_) return false;
      RgbdMessage rgbd;
      rgbd.received = received;
      if (!io::DecodeRgbdFrameHeader(data, size, &rgbd.frame, &rgbd.images, &error)) {
        return Reject(input, "undecodable RGB-D frame", error);
      }
      for (const sensor::PinholeIntrinsics* k : {&rgbd.frame.color_intrinsics, &rgbd.frame.depth_intrinsics}) {
        if (int64_t{k->width} * k->height > options_.max_image_pixels) {
          return Reject(input, "RGB-D image too large",
                        std::to_string(k->width) + "x" + std::to_string(k->height) +
                            " pixels, more than daemon.max_image_pixels " +
                            std::to_string(options_.max_image_pixels) + "; dropped");
        }
      }
      return Admit(input, std::move(rgbd));
    }
    case kNumInputChannels:
      break;
  }
  return false;
}

bool Intake::DecodeImages(RgbdMessage* message) {
  std::string error;
  if (!io::DecodeRgbdImages(message->images, &message->frame, &error)) {
    return Reject(kRgbdChannel, "undecodable RGB-D frame", error);
  }
  message->images = io::RgbdImageData();
  return true;
}

void Intake::Close() {
  sensor_queue_.Close();
  rgbd_queue_.Close();
}

std::vector<HealthReport::Channel> Intake::ChannelHealth() const {
  std::vector<HealthReport::Channel> rows;
  const int sensor_depth = static_cast<int>(sensor_queue_.size());
  for (int i = 0; i < kNumInputChannels; ++i) {
    if (names_[i].empty()) continue;
    HealthReport::Channel row;
    row.name = names_[i];
    row.received = counters_[i].received.load();
    row.dropped = counters_[i].dropped.load();
    row.malformed = counters_[i].malformed.load();
    row.skipped = counters_[i].skipped.load();
    row.queue_depth = i == kRgbdChannel ? static_cast<int>(rgbd_queue_.size()) : sensor_depth;
    rows.push_back(row);
  }
  return rows;
}

}  // namespace daemon
}  // namespace fusemap
