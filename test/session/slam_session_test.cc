#include "fusemap/session/slam_session.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <deque>
#include <filesystem>
#include <string>
#include <vector>

#include "fusemap/io/lcm_conversions.h"
#include "fusemap/pose_graph/moved_submaps.h"
#include "testing/room_drive_log.h"
#include "testing/room_slam_config.h"
#include "testing/wall_frame.h"

namespace fusemap {
namespace session {
namespace {

constexpr double kStartS = 1700000000.0;

io::SlamConfig CloudConfig() {
  io::SlamConfig config = test_world::RoomSlamConfig();
  config.cloud.enabled = true;
  config.cloud.frame.outlier_mean_k = 0;
  config.cloud.binder.remove_dynamic = false;
  return config;
}

// The room drive decoded, with a wall frame every fifth scan, fed to `session` in log order.
// `between_scans` runs after every scan (a stand-in for another thread draining a queue).
template <typename F>
void Drive(SlamSession* session, F&& between_scans) {
  const io::SlamConfig& config = session->config();
  int scans = 0;
  std::string error;
  for (const auto& message : test_world::RoomDriveMessages(0.15, kStartS, 7)) {
    const int size = static_cast<int>(message.data.size());
    if (message.channel == "LIDAR") {
      sensor::LaserScan scan;
      ASSERT_TRUE(io::DecodeLaserScan(message.data.data(), size, config.lidar, &scan, &error));
      if (scans++ % 5 == 0) session->AddRgbdFrame(test_world::WallFrame(scan.stamp_s - 0.05));
      session->AddScan(scan);
      between_scans();
    } else {
      sensor::OdometryData odometry;
      ASSERT_TRUE(io::DecodeOdometry(message.data.data(), size, &odometry, &error));
      session->AddOdometry(odometry);
    }
  }
  session->Finish();
}

// fusemapd hands the cloud updates to another thread through a queue (SetCloudSink);
// fusemap_offline applies them inline. Same updates in the same order: the same cloud.
TEST(SlamSessionTest, CloudThroughASinkEqualsCloudInline) {
  common::InlineExecutor executor;
  SlamSession inline_session(CloudConfig(), &executor);
  Drive(&inline_session, [] {});

  SlamSession queued_session(CloudConfig(), &executor);
  std::deque<CloudPoseUpdate> queue;
  queued_session.SetCloudSink([&queue](CloudPoseUpdate&& u) { queue.push_back(std::move(u)); });
  CloudStage* stage = queued_session.cloud_stage();
  ASSERT_NE(stage, nullptr);
  // As fusemapd's RGB-D thread: poses first, then frames; the frame of a scan arrives with it.
  const auto drain = [&] {
    while (!queue.empty()) {
      stage->Apply(queue.front());
      queue.pop_front();
    }
  };
  int scans = 0;
  const io::SlamConfig& config = queued_session.config();
  std::string error;
  for (const auto& message : test_world::RoomDriveMessages(0.15, kStartS, 7)) {
    const int size = static_cast<int>(message.data.size());
    if (message.channel == "LIDAR") {
      sensor::LaserScan scan;
      ASSERT_TRUE(io::DecodeLaserScan(message.data.data(), size, config.lidar, &scan, &error));
      if (scans++ % 5 == 0) stage->AddFrame(test_world::WallFrame(scan.stamp_s - 0.05));
      queued_session.AddScan(scan);
      drain();
    } else {
      sensor::OdometryData odometry;
      ASSERT_TRUE(io::DecodeOdometry(message.data.data(), size, &odometry, &error));
      queued_session.AddOdometry(odometry);
    }
  }
  queued_session.Finish();
  drain();
  stage->Finish();

  const auto& a = inline_session.cloud_stage()->mapper();
  const auto& b = stage->mapper();
  ASSERT_GT(a.stats().frames_bound, 10);
  EXPECT_EQ(a.stats().frames_bound, b.stats().frames_bound);
  const auto cloud_a = a.binder().GlobalCloud();
  const auto cloud_b = b.binder().GlobalCloud();
  ASSERT_EQ(cloud_a->size(), cloud_b->size());
  for (size_t i = 0; i < cloud_a->size(); i += 97) {
    EXPECT_EQ(cloud_a->at(i).x, cloud_b->at(i).x);
    EXPECT_EQ(cloud_a->at(i).y, cloud_b->at(i).y);
  }
}

// The cloud follows the pose graph: after the run every submap the cloud holds sits where the
// final optimisation put it (within the one "moved" threshold).
TEST(SlamSessionTest, CloudSubmapsFollowTheFinalOptimisation) {
  common::InlineExecutor executor;
  SlamSession session(CloudConfig(), &executor);
  Drive(&session, [] {});
  const auto& stats = session.builder().pose_graph().stats();
  ASSERT_GT(stats.optimizations, 0);
  ASSERT_GT(stats.loop_closures_found, 0);
  const auto snapshot = session.builder().pose_graph().Snapshot();
  const auto& placed = session.cloud_stage()->mapper().T_map_submaps();
  ASSERT_EQ(placed.size(), snapshot->T_map_submaps.size());
  for (const auto& [submap, T_map_submap] : placed) {
    EXPECT_FALSE(pose_graph::SubmapMoved(T_map_submap, snapshot->T_map_submaps.at(submap)))
        << "submap " << submap;
  }
}

TEST(SlamSessionTest, OdometryGoingBackIsNotRecorded) {
  common::InlineExecutor executor;
  io::SlamConfig config = test_world::RoomSlamConfig();
  config.cloud.enabled = false;
  SlamSession session(config, &executor);
  EXPECT_EQ(session.cloud_stage(), nullptr);
  EXPECT_TRUE(session.AddOdometry({kStartS + 1.0, common::Rigid2d::Identity()}));
  EXPECT_FALSE(session.AddOdometry({kStartS + 0.5, common::Rigid2d::Identity()}));
  EXPECT_TRUE(session.AddOdometry({kStartS + 1.0, common::Rigid2d::Identity()}));
  EXPECT_EQ(session.odometry().size(), 2u);
}

TEST(SlamSessionTest, WritesTheRunOutputs) {
  common::InlineExecutor executor;
  SlamSession session(CloudConfig(), &executor);
  Drive(&session, [] {});
  const std::string dir = ::testing::TempDir() + "/slam_session_outputs";
  std::filesystem::remove_all(dir);
  RunOutputsReport report;
  std::string error;
  ASSERT_TRUE(session.WriteOutputs(dir, &report, &error)) << error;
  EXPECT_TRUE(report.wrote_cloud);
  for (const char* name : {"trajectory.tum", "nodes.tum", "odometry.tum", "map.pgm", "cloud.ply"}) {
    EXPECT_TRUE(std::filesystem::exists(dir + "/" + name)) << name;
  }
}

}  // namespace
}  // namespace session
}  // namespace fusemap
