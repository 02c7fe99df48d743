// Issue 18, item 3, end to end: one odometry message at x = 1e300 early in a log hung fusemapd
// and fusemap_offline for good (the grid's growth loop overflowed). The decoders now refuse
// positions beyond 1000 km (item 8), so this log jumps 100 km instead: within the decoders'
// bounds, it still reaches local SLAM and the grids, and both programs must finish the log with
// a sane map.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

#include "fusemap/daemon/engine.h"
#include "fusemap/io/lcm_conversions.h"
#include "fusemap/io/lcm_log.h"
#include "fusemap/io/tum_trajectory.h"
#include "testing/null_publisher.h"
#include "testing/room_drive_log.h"
#include "testing/room_slam_config.h"

namespace fusemap {
namespace daemon {
namespace {

constexpr double kStartS = 1700000000.0;

// The room drive with the odometry message just before the fourth scan moved 100 km away: that
// scan's prediction comes straight from it.
std::string WriteLog(const std::string& path, int* scans) {
  auto messages = test_world::RoomDriveMessages(0.15, kStartS, 42);
  *scans = 0;
  for (size_t i = 1; i < messages.size(); ++i) {
    if (messages[i].channel == "LIDAR" && ++*scans == 4) {
      EXPECT_EQ(messages[i - 1].channel, "ODOMETRY");
      messages[i - 1].data =
          io::EncodeOdometry({messages[i - 1].stamp_s, common::Rigid2d(1e5, -1e5, 0.0)});
    }
  }
  io::LcmLogWriter writer;
  std::string error;
  EXPECT_TRUE(writer.Open(path, &error)) << error;
  *scans = 0;
  for (const auto& message : messages) {
    writer.Write(message.channel, io::StampToUtime(message.stamp_s), message.data.data(), message.data.size());
    if (message.channel == "LIDAR") ++*scans;
  }
  writer.Close();
  return path;
}

using test_world::NullPublisher;

// The room is 10 m across: every node must stay within it (with drift to spare).
void ExpectSane(const std::vector<pose_graph::MapBuilder2D::TimedPose2d>& nodes) {
  ASSERT_GT(nodes.size(), 50u);
  for (const auto& node : nodes) ASSERT_LT(node.pose.translation().norm(), 20.0) << node.stamp_s;
}

TEST(FarOdometryReplayTest, DaemonEngineFinishesTheLog) {
  int scans = 0;
  const std::string log = WriteLog(::testing::TempDir() + "/far_odometry_engine.lcm", &scans);
  RateLimitedLog quiet(1e9, [] { return 0.0; }, [](const std::string&) {});
  NullPublisher silent;
  DaemonOptions options;
  Engine engine(test_world::RoomSlamConfig(), options, 1, OverflowPolicy::kBlock, &silent, &quiet);
  engine.Start();
  io::LcmLogReader reader;
  std::string error;
  ASSERT_TRUE(reader.Open(log, &error)) << error;
  io::LogEvent event;
  while (reader.Next(&event)) {
    engine.intake().OnMessage(event.channel, event.data.data(), static_cast<int>(event.data.size()));
  }
  engine.Finish();
  EXPECT_EQ(engine.scans_processed(), scans);
  ExpectSane(engine.finished_builder().NodePoses());
}

TEST(FarOdometryReplayTest, OfflineRunnerFinishesTheLog) {
#ifndef FUSEMAP_OFFLINE_BINARY
  GTEST_SKIP() << "fusemap_offline is not part of this build";
#else
  int scans = 0;
  const std::string log = WriteLog(::testing::TempDir() + "/far_odometry_offline.lcm", &scans);
  const std::string out = ::testing::TempDir() + "/far_odometry_offline_out";
  // `timeout`: before the fix the runner never returned.
  const std::string command = std::string("timeout 120 ") + FUSEMAP_OFFLINE_BINARY + " --log " + log +
                              " --config " FUSEMAP_SOURCE_DIR "/config/sim.yaml --out " + out +
                              " --quiet > " + out + ".stdout 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << command << "\n"
                                             << std::ifstream(out + ".stdout").rdbuf();
  eval::Trajectory nodes;
  std::string error;
  ASSERT_TRUE(io::ReadTumTrajectoryFile(out + "/nodes.tum", &nodes, &error)) << error;
  std::ifstream stdout_file(out + ".stdout");
  const std::string printed((std::istreambuf_iterator<char>(stdout_file)), std::istreambuf_iterator<char>());
  EXPECT_NE(printed.find("absurd_predictions=2 insertions_refused=0"), std::string::npos) << printed;
  ASSERT_GT(nodes.size(), 50u);
  for (const auto& node : nodes) ASSERT_LT(node.pose.translation().norm(), 20.0) << node.stamp_s;
#endif
}

}  // namespace
}  // namespace daemon
}  // namespace fusemap
