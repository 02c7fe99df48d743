// Bounded random input for the whole daemon engine (issue 18 "Also"): a small valid log of
// laser, odometry, IMU and RGB-D messages, with mutants mixed in at random places (stamps far
// ahead, a little or far behind, utime -2^62, huge or NaN values, truncated and zero-size
// payloads), replayed in-process through the engine with a fixed seed. The properties: it ends
// within a watchdog's limit, nothing crashes, every valid message is mapped exactly as without
// the mutants (the same nodes, odometry record and trajectory.tum), and the malformed counters
// count exactly the mutants of each channel. It would have caught issue 18 items 6, 7 and 8.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "fusemap/daemon/engine.h"
#include "fusemap/io/lcm_conversions.h"
#include "fusemap/io/rgbd_conversions.h"
#include "fusemap_lcm/rgbd_frame_t.hpp"
#include "testing/null_publisher.h"
#include "testing/room_drive_log.h"
#include "testing/room_slam_config.h"

namespace fusemap {
namespace daemon {
namespace {

constexpr double kStartS = 1700000000.0;
constexpr auto kWatchdog = std::chrono::seconds(120);
const char* const kChannels[] = {"LIDAR", "ODOMETRY", "IMU", "RGBD"};

struct Message {
  int channel = 0;  // InputChannel
  double stamp_s = 0.0;
  std::vector<uint8_t> data;
  bool mutant = false;
};

sensor::ImuData Imu(double stamp_s) {
  sensor::ImuData imu;
  imu.stamp_s = stamp_s;
  imu.linear_acceleration_mps2 = Eigen::Vector3d(0.0, 0.0, 9.81);
  return imu;
}

std::vector<uint8_t> Rgbd(double stamp_s) {
  constexpr int width = 8, height = 6;
  sensor::RgbdFrame frame;
  frame.stamp_s = stamp_s;
  frame.color_intrinsics = {width, height, 5.0, 5.0, 4.0, 3.0};
  frame.depth_intrinsics = frame.color_intrinsics;
  frame.color_rgb.assign(static_cast<size_t>(width) * height * 3, 90);
  frame.depth_mm.assign(static_cast<size_t>(width) * height, 1500);
  io::RgbdEncodeOptions options;
  options.color_encoding = "rgb8";
  options.depth_encoding = "mono16";
  std::vector<uint8_t> bytes;
  std::string error;
  EXPECT_TRUE(io::EncodeRgbdFrame(frame, options, &bytes, &error)) << error;
  return bytes;
}

// A frame whose colour and depth images have zero bytes (the wire allows it).
std::vector<uint8_t> WithEmptyImages(const std::vector<uint8_t>& bytes) {
  fusemap_lcm::rgbd_frame_t msg;
  EXPECT_EQ(msg.decode(bytes.data(), 0, static_cast<int>(bytes.size())),
            static_cast<int>(bytes.size()));
  msg.color_size = 0;
  msg.color_data.clear();
  msg.depth_size = 0;
  msg.depth_data.clear();
  std::vector<uint8_t> empty(msg.getEncodedSize());
  msg.encode(empty.data(), 0, static_cast<int>(empty.size()));
  return empty;
}

// The room drive with IMU at 40 Hz and an RGB-D frame every other scan.
std::vector<Message> ValidLog() {
  std::vector<Message> log;
  int scans = 0;
  for (auto& m : test_world::RoomDriveMessages(0.15, kStartS, 7)) {
    const bool laser = m.channel == "LIDAR";
    log.push_back({laser ? kLidarChannel : kOdometryChannel, m.stamp_s, std::move(m.data)});
    if (!laser) continue;
    log.push_back({kImuChannel, m.stamp_s + 0.02, io::EncodeImu(Imu(m.stamp_s + 0.02))});
    log.push_back({kImuChannel, m.stamp_s + 0.045, io::EncodeImu(Imu(m.stamp_s + 0.045))});
    if (scans++ % 2 == 0) log.push_back({kRgbdChannel, m.stamp_s + 0.01, Rgbd(m.stamp_s + 0.01)});
  }
  return log;
}

// A mutant of a message of `channel` near `stamp_s`, as a broken driver, a corrupt log or a
// hostile sender produces it. Each costs itself only: the engine must count it as malformed.
Message Mutant(int channel, double stamp_s, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int kind = static_cast<int>(rng() % 7);
  double stamp = stamp_s;
  if (kind == 0) stamp += 1e5 + 1e8 * unit(rng);  // days to years ahead (item 6)
  if (kind == 1) stamp -= 0.5 + 3.0 * unit(rng);  // a little behind: backwards
  if (kind == 2) stamp -= 1e8 + 1e8 * unit(rng);  // years behind: no log loop (item 7)
  if (kind == 3) stamp = -4611686018427.387904;   // utime -2^62 (item 7)
  std::vector<uint8_t> data;
  const bool bad_value = kind == 4;  // huge or NaN values (item 8)
  const double huge = unit(rng) < 0.5 ? std::numeric_limits<double>::quiet_NaN()
                                      : (unit(rng) < 0.5 ? 1e300 : -3e7);
  switch (channel) {
    case kLidarChannel: {
      sensor::LaserScan scan;
      scan.stamp_s = stamp;
      scan.angle_min_rad = -1.5f;
      scan.angle_increment_rad = 0.03f;
      scan.range_min_m = 0.1f;
      scan.range_max_m = 12.f;
      scan.ranges_m.assign(100, 2.f);
      if (bad_value && unit(rng) < 0.5) {
        scan.range_max_m = 1e30f;  // returns up to 1e30 m would grow the grid without bound
        scan.ranges_m.assign(100, 1e29f);
      } else if (bad_value) {
        scan.ranges_m.assign(100, std::numeric_limits<float>::quiet_NaN());
      }
      data = io::EncodeLaserScan(scan);
      break;
    }
    case kOdometryChannel:
      data = io::EncodeOdometry({stamp, common::Rigid2d(bad_value ? huge : 1.0, 0.0, 0.0)});
      break;
    case kImuChannel: {
      sensor::ImuData imu = Imu(stamp);
      if (bad_value) imu.angular_velocity_radps.z() = huge;
      data = io::EncodeImu(imu);
      break;
    }
    default:
      data = Rgbd(stamp);
      if (bad_value) data = WithEmptyImages(data);
      break;
  }
  if (kind == 5) data.resize(data.size() / 2);  // truncated
  if (kind == 6) data.clear();                  // zero-size payload
  return {channel, stamp, std::move(data), true};
}

// Every valid message once, a mutant after about every eighth, never before each channel's
// first valid message (before it nothing says "backwards").
std::vector<Message> WithMutants(const std::vector<Message>& valid, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<Message> log;
  for (size_t i = 0; i < valid.size(); ++i) {
    log.push_back(valid[i]);
    if (i > 20 && rng() % 8 == 0) {
      log.push_back(Mutant(static_cast<int>(rng() % kNumInputChannels), valid[i].stamp_s, rng));
    }
  }
  return log;
}

struct RunResult {
  std::vector<pose_graph::MapBuilder2D::TimedPose2d> nodes;
  std::vector<double> odometry_stamps;
  std::vector<double> rgbd_stamps;
  std::vector<HealthReport::Channel> channels;
  int64_t time_resets = 0;
  std::string trajectory_tum;
};

RunResult Replay(const std::vector<Message>& log, const std::string& dir) {
  RateLimitedLog quiet(1e9, [] { return 0.0; }, [](const std::string&) {});
  test_world::NullPublisher publisher;
  RunResult result;
  Engine engine(test_world::RoomSlamConfig(), DaemonOptions(), 1, OverflowPolicy::kBlock,
                &publisher, &quiet);
  engine.SetRgbdConsumer([&result](RgbdMessage&& m) { result.rgbd_stamps.push_back(m.frame.stamp_s); });
  engine.Start();
  for (const Message& m : log) {
    engine.intake().OnMessage(kChannels[m.channel], m.data.data(), static_cast<int>(m.data.size()));
  }
  engine.Finish();
  result.nodes = engine.finished_builder().NodePoses();
  for (const auto& o : engine.odometry()) result.odometry_stamps.push_back(o.stamp_s);
  result.channels = engine.Health().channels;
  result.time_resets = engine.Health().time_resets;
  std::string error;
  EXPECT_TRUE(engine.WriteOutputs(dir, &error)) << error;
  std::ifstream in(dir + "/trajectory.tum");
  std::stringstream text;
  text << in.rdbuf();
  result.trajectory_tum = text.str();
  return result;
}

// Runs `body` on a thread and fails the test (ending the process: a hung thread cannot be
// joined) if it has not finished within kWatchdog.
template <typename Body>
void WithWatchdog(Body body) {
  std::packaged_task<void()> task(body);
  std::future<void> done = task.get_future();
  std::thread worker(std::move(task));
  if (done.wait_for(kWatchdog) != std::future_status::ready) {
    ADD_FAILURE() << "the engine did not finish within " << kWatchdog.count() << " s: a hang";
    std::fflush(stdout);
    std::_Exit(1);
  }
  worker.join();
  done.get();
}

TEST(EngineFuzzTest, MutantsCostThemselvesOnlyAndAreCounted) {
  const auto valid = ValidLog();
  const std::string dir = ::testing::TempDir() + "/engine_fuzz_test";
  std::filesystem::remove_all(dir);
  RunResult clean;
  WithWatchdog([&] { clean = Replay(valid, dir + "/clean"); });
  ASSERT_GT(clean.nodes.size(), 50u);
  for (unsigned seed : {1u, 2u, 3u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const auto log = WithMutants(valid, seed);
    std::vector<int> mutants(kNumInputChannels, 0);
    for (const Message& m : log) mutants[m.channel] += m.mutant;
    ASSERT_GT(log.size(), valid.size() + 40);
    RunResult fuzzed;
    WithWatchdog([&] { fuzzed = Replay(log, dir + "/seed" + std::to_string(seed)); });
    ASSERT_EQ(fuzzed.nodes.size(), clean.nodes.size());
    for (size_t i = 0; i < clean.nodes.size(); ++i) {
      ASSERT_EQ(fuzzed.nodes[i].stamp_s, clean.nodes[i].stamp_s) << i;
      ASSERT_LT((fuzzed.nodes[i].pose.translation() - clean.nodes[i].pose.translation()).norm(),
                1e-9)
          << i;
    }
    EXPECT_EQ(fuzzed.odometry_stamps, clean.odometry_stamps);
    EXPECT_EQ(fuzzed.rgbd_stamps, clean.rgbd_stamps);
    EXPECT_EQ(fuzzed.trajectory_tum, clean.trajectory_tum);
    EXPECT_EQ(fuzzed.time_resets, 0);
    ASSERT_EQ(fuzzed.channels.size(), static_cast<size_t>(kNumInputChannels));
    for (int c = 0; c < kNumInputChannels; ++c) {
      EXPECT_EQ(fuzzed.channels[c].malformed, mutants[c]) << kChannels[c];
      EXPECT_EQ(fuzzed.channels[c].dropped, 0) << kChannels[c];
    }
  }
}

// Item 3 (grid overflow) and item 1 (zero-size JPEG): an odometry jump of 100 km (within the
// decoder's bounds) and compressed images of zero size must neither hang nor crash the engine.
TEST(EngineFuzzTest, FarOdometryJumpAndEmptyJpegDoNotHang) {
  auto log = ValidLog();
  const double stamp_s = log[30].stamp_s + 0.001;
  log.insert(log.begin() + 31, Message{kOdometryChannel, stamp_s,
                                       io::EncodeOdometry({stamp_s, common::Rigid2d(1e5, 0, 0)}),
                                       false});
  sensor::RgbdFrame frame;
  frame.stamp_s = stamp_s;
  frame.color_intrinsics = {8, 6, 5.0, 5.0, 4.0, 3.0};
  frame.depth_intrinsics = frame.color_intrinsics;
  io::RgbdEncodeOptions options;
  options.color_encoding = "jpeg";
  options.depth_encoding = "png16";
  std::vector<uint8_t> bytes;
  std::string error;
  io::EncodeRgbdFrame(frame, options, &bytes, &error);
  log.insert(log.begin() + 32, Message{kRgbdChannel, stamp_s, bytes, true});
  RunResult result;
  WithWatchdog([&] { result = Replay(log, ::testing::TempDir() + "/engine_fuzz_far"); });
  EXPECT_FALSE(result.nodes.empty());
  ASSERT_EQ(result.channels.size(), static_cast<size_t>(kNumInputChannels));
  // The empty JPEG is refused as malformed, not decoded.
  EXPECT_EQ(result.channels[kRgbdChannel].malformed, 1);
}

}  // namespace
}  // namespace daemon
}  // namespace fusemap
