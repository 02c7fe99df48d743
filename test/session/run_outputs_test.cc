#include "fusemap/session/run_outputs.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "fusemap/io/lcm_conversions.h"
#include "fusemap/io/loop_tables_file.h"
#include "fusemap/session/slam_session.h"
#include "testing/room_drive_log.h"
#include "testing/room_slam_config.h"

namespace fusemap {
namespace session {
namespace {

TEST(RunOutputsTest, SubmapAnchorsAndLoopTableMatchTheGraph) {
  common::InlineExecutor executor;
  SlamSession session(test_world::RoomSlamConfig(), &executor);
  std::string error;
  for (const auto& message : test_world::RoomDriveMessages(0.15, 1700000000.0, 7)) {
    const int size = static_cast<int>(message.data.size());
    if (message.channel == "LIDAR") {
      sensor::LaserScan scan;
      ASSERT_TRUE(io::DecodeLaserScan(message.data.data(), size, session.config().lidar, &scan, &error));
      session.AddScan(scan);
    } else {
      sensor::OdometryData odometry;
      ASSERT_TRUE(io::DecodeOdometry(message.data.data(), size, &odometry, &error));
      session.AddOdometry(odometry);
    }
  }
  session.Finish();
  const std::string dir = ::testing::TempDir() + "/run_outputs_loop_tables";
  std::filesystem::remove_all(dir);
  RunOutputsReport report;
  ASSERT_TRUE(session.WriteOutputs(dir, &report, &error)) << error;

  std::vector<eval::SubmapAnchor> submaps;
  std::vector<eval::LoopRecord> loops;
  ASSERT_TRUE(io::ReadSubmapAnchorsFile(dir + "/submaps.tsv", &submaps, &error)) << error;
  ASSERT_TRUE(io::ReadLoopsFile(dir + "/loops.tsv", &loops, &error)) << error;
  const auto snapshot = session.builder().pose_graph().Snapshot();
  ASSERT_EQ(submaps.size(), snapshot->T_map_submaps.size());
  ASSERT_GE(submaps.size(), 2u);
  EXPECT_EQ(submaps[0].first_node, 0);
  for (size_t i = 0; i < submaps.size(); ++i) {
    EXPECT_EQ(submaps[i].submap, static_cast<int>(i));
    if (i > 0) {
      EXPECT_GT(submaps[i].first_node, submaps[i - 1].first_node);
    }
    EXPECT_NEAR(submaps[i].T_map_submap.x(), snapshot->T_map_submaps[i].x(), 1e-6);
  }
  // Each loop is a laser constraint of the final graph: its pose agrees with the optimised
  // estimate to well within a metre on this easy drive.
  const auto nodes = session.builder().NodePoses();
  for (const eval::LoopRecord& loop : loops) {
    EXPECT_EQ(loop.decision, "laser_kept");
    ASSERT_LT(loop.node, static_cast<int>(nodes.size()));
    ASSERT_LT(loop.submap, static_cast<int>(submaps.size()));
    const common::Rigid2d estimate =
        snapshot->T_map_submaps[loop.submap].inverse() * nodes[loop.node].pose;
    EXPECT_LT((estimate.translation() - loop.T_submap_node.translation()).norm(), 1.0);
  }
}

}  // namespace
}  // namespace session
}  // namespace fusemap
