// file:// replay through the whole daemon engine (LCM file provider, intake, queues, SLAM
// thread, publisher) against a session::SlamSession fed directly in log order as
// fusemap_offline does:
// with one thread the trajectories must be identical, bit for bit.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <mutex>
#include <random>
#include <string>
#include <vector>

#include "fusemap/common/math.h"
#include "fusemap/daemon/engine.h"
#include "fusemap/daemon/lcm_input.h"
#include "fusemap/session/slam_session.h"
#include "fusemap/io/lcm_conversions.h"
#include "fusemap/io/lcm_log.h"
#include "testing/room_drive_log.h"
#include "testing/room_slam_config.h"
#include "testing/synthetic_room.h"

namespace fusemap {
namespace daemon {
namespace {

constexpr double kStepM = 0.15;
constexpr double kStartS = 1700000000.0;


// The room drive (testing/room_drive_log.h) as an LCM log, with a malformed LIDAR message after
// every 20th scan that must not change anything.
std::string WriteLog(const std::string& path) {
  io::LcmLogWriter writer;
  std::string error;
  EXPECT_TRUE(writer.Open(path, &error)) << error;
  int scans = 0;
  for (const auto& message : test_world::RoomDriveMessages(kStepM, kStartS, 42)) {
    const int64_t utime = io::StampToUtime(message.stamp_s);
    writer.Write(message.channel, utime, message.data.data(), message.data.size());
    if (message.channel == "LIDAR" && scans++ % 20 == 0) {
      const auto junk = std::vector<uint8_t>(5, 0xab);
      writer.Write("LIDAR", utime, junk.data(), junk.size());
    }
  }
  writer.Close();
  return path;
}

// The session fed in log order on this thread, as fusemap_offline feeds it, over the same log.
std::vector<pose_graph::MapBuilder2D::TimedPose2d> OfflineTrajectory(const std::string& log,
                                                                     const io::SlamConfig& config) {
  common::InlineExecutor executor;
  session::SlamSession session(config, &executor);
  io::LcmLogReader reader;
  std::string error;
  EXPECT_TRUE(reader.Open(log, &error)) << error;
  io::LogEvent event;
  while (reader.Next(&event)) {
    const int size = static_cast<int>(event.data.size());
    if (event.channel == config.channels.lidar) {
      sensor::LaserScan scan;
      if (io::DecodeLaserScan(event.data.data(), size, config.lidar, &scan, &error)) {
        session.AddScan(scan);
      }
    } else if (event.channel == config.channels.odometry) {
      sensor::OdometryData data;
      if (io::DecodeOdometry(event.data.data(), size, &data, &error)) session.AddOdometry(data);
    }
  }
  session.Finish();
  return pose_graph::DensifyWithOdometry(session.builder().NodePoses(), session.odometry());
}

class RecordingPublisher : public Publisher {
 public:
  void PublishPose(double, const common::Rigid2d&) override { ++poses; }
  void PublishSubmapList(double, const pose_graph::PoseGraphSnapshot& s) override {
    ++submap_lists;
    last_submaps = static_cast<int>(s.T_map_submaps.size());
  }
  void PublishLoopClosure(double, int n, const pose_graph::PoseGraph2D::Stats&, int,
                          const io::LoopNote&) override {
    loop_closures += n;
  }
  void PublishHealth(double, const HealthReport& r) override {
    ++health;
    last_health = r;
  }
  // The engine's SLAM thread writes `poses`, its report thread the rest; the test reads after
  // Finish() joined both.
  int poses = 0, submap_lists = 0, loop_closures = 0, health = 0, last_submaps = 0;
  HealthReport last_health;
};

TEST(ReplayTest, FileReplayWithOneThreadEqualsOfflineRunnerBitForBit) {
  const std::string log = WriteLog(::testing::TempDir() + "/daemon_replay.lcm");
  const io::SlamConfig config = test_world::RoomSlamConfig();
  const auto expected = OfflineTrajectory(log, config);
  ASSERT_GT(expected.size(), 100u);

  DaemonOptions options;
  options.sensor_queue_size = 8;  // small, to exercise blocking on the file provider
  const std::string url = "file://" + log + "?speed=0";
  ASSERT_EQ(PolicyForUrl(url), OverflowPolicy::kBlock);
  RateLimitedLog quiet(1e9, [] { return 0.0; }, [](const std::string&) {});
  RecordingPublisher publisher;
  Engine engine(config, options, 1, PolicyForUrl(url), &publisher, &quiet);
  LcmInput input;
  std::string error;
  ASSERT_TRUE(input.Open(url, &error)) << error;
  EXPECT_EQ(input.publish_handle(), nullptr);
  input.Subscribe(&engine.intake());
  engine.Start();
  std::atomic<bool> stop{false};
  EXPECT_EQ(input.Run(stop, 1000), LcmInput::End::kEndOfLog);
  engine.Finish();

  const auto actual = pose_graph::DensifyWithOdometry(engine.finished_builder().NodePoses(),
                                                      engine.odometry());
  ASSERT_EQ(actual.size(), expected.size());
  for (size_t i = 0; i < actual.size(); ++i) {
    ASSERT_EQ(actual[i].stamp_s, expected[i].stamp_s) << i;
    ASSERT_EQ(actual[i].pose.translation().x(), expected[i].pose.translation().x()) << i;
    ASSERT_EQ(actual[i].pose.translation().y(), expected[i].pose.translation().y()) << i;
    ASSERT_EQ(actual[i].pose.angle_rad(), expected[i].pose.angle_rad()) << i;
  }
  const auto stats = engine.finished_builder().pose_graph().stats();
  EXPECT_GT(stats.loop_closures_found, 0);
  EXPECT_GT(stats.optimizations, 0);
  // The junk LIDAR messages were counted as malformed, nothing was dropped on overflow.
  const HealthReport health = engine.Health();
  EXPECT_EQ(health.channels[kLidarChannel].malformed, 6);  // i % 20 == 0 of 115 scans
  EXPECT_EQ(health.channels[kLidarChannel].dropped, 0);
  EXPECT_EQ(health.channels[kOdometryChannel].dropped, 0);
  EXPECT_GT(publisher.poses, 0);
  EXPECT_GE(publisher.submap_lists, 1);
  EXPECT_EQ(publisher.last_submaps, stats.submaps);
  EXPECT_EQ(publisher.loop_closures, stats.loop_closures_found);
  EXPECT_GE(publisher.health, 1);
  EXPECT_EQ(publisher.last_health.nodes, stats.nodes);

  const std::string out = ::testing::TempDir() + "/daemon_replay_out";
  ASSERT_TRUE(engine.WriteOutputs(out, &error)) << error;
  for (const char* name : {"trajectory.tum", "nodes.tum", "map.pgm", "map.yaml", "map.png"}) {
    FILE* f = std::fopen((out + "/" + name).c_str(), "rb");
    EXPECT_NE(f, nullptr) << name;
    if (f != nullptr) std::fclose(f);
  }
}

TEST(ReplayTest, DirectFeedingWithThreadPoolFinishesEverything) {
  const std::string log = WriteLog(::testing::TempDir() + "/daemon_direct.lcm");
  RateLimitedLog quiet(1e9, [] { return 0.0; }, [](const std::string&) {});
  RecordingPublisher publisher;
  DaemonOptions options;
  Engine engine(test_world::RoomSlamConfig(), options, 2, OverflowPolicy::kBlock, &publisher, &quiet);
  engine.Start();
  io::LcmLogReader reader;
  std::string error;
  ASSERT_TRUE(reader.Open(log, &error)) << error;
  io::LogEvent event;
  int scans = 0;
  while (reader.Next(&event)) {
    if (engine.intake().OnMessage(event.channel, event.data.data(),
                                  static_cast<int>(event.data.size())) &&
        event.channel == "LIDAR") {
      ++scans;
    }
  }
  engine.Finish();
  EXPECT_EQ(engine.scans_processed(), scans);
  EXPECT_GT(engine.finished_builder().pose_graph().stats().optimizations, 0);
  EXPECT_EQ(publisher.last_submaps, engine.finished_builder().pose_graph().stats().submaps);
}

}  // namespace
}  // namespace daemon
}  // namespace fusemap
