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

// The room drive decoded and fed to `session` in log order, with a wall frame before every
// fifth scan handed to `add_frame`; `after_scan` runs after every scan (a stand-in for another
// thread draining a queue).
template <typename AddFrame, typename AfterScan>
void Drive(SlamSession* session, AddFrame&& add_frame, AfterScan&& after_scan) {
  const io::SlamConfig& config = session->config();
  int scans = 0;
  std::string error;
  for (const auto& message : test_world::RoomDriveMessages(0.15, kStartS, 7)) {
    const int size = static_cast<int>(message.data.size());
    if (message.channel == "LIDAR") {
      sensor::LaserScan scan;
      ASSERT_TRUE(io::DecodeLaserScan(message.data.data(), size, config.lidar, &scan, &error));
      if (scans++ % 5 == 0) add_frame(test_world::WallFrame(scan.stamp_s - 0.05));
      session->AddScan(scan);
      after_scan();
    } else {
      sensor::OdometryData odometry;
      ASSERT_TRUE(io::DecodeOdometry(message.data.data(), size, &odometry, &error));
      session->AddOdometry(odometry);
    }
  }
  session->Finish();
}

// As fusemap_offline: the cloud stage inline.
void DriveInline(SlamSession* session) {
  Drive(
      session, [session](const sensor::RgbdFrame& frame) { session->AddRgbdFrame(frame); }, [] {});
}

// fusemapd hands the cloud updates to another thread through a queue (SetCloudSink);
// fusemap_offline applies them inline. Same updates in the same order: the same cloud.
TEST(SlamSessionTest, CloudThroughASinkEqualsCloudInline) {
  common::InlineExecutor executor;
  SlamSession inline_session(CloudConfig(), &executor);
  DriveInline(&inline_session);

  SlamSession queued_session(CloudConfig(), &executor);
  std::deque<CloudPoseUpdate> queue;
  queued_session.SetCloudSink([&queue](CloudPoseUpdate&& u) { queue.push_back(std::move(u)); });
  CloudStage* stage = queued_session.cloud_stage();
  ASSERT_NE(stage, nullptr);
  // As fusemapd's RGB-D thread: it alone touches the stage, taking poses as they are queued.
  const auto drain = [&] {
    while (!queue.empty()) {
      stage->Apply(queue.front());
      queue.pop_front();
    }
  };
  Drive(
      &queued_session, [stage](const sensor::RgbdFrame& frame) { stage->AddFrame(frame); }, drain);
  drain();  // the final optimisation's placements
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
  DriveInline(&session);
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
  DriveInline(&session);
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
