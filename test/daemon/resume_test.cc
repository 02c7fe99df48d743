// Checkpoint and --resume through the engine: a run stopped right after a checkpoint, resumed by
// a fresh engine from the file, must end where the uninterrupted run ends (one thread, so both
// are deterministic), with a trajectory that covers the whole run. Plus the resume policy:
// corrupt checkpoint -> .prev, other version refused, other config warned about.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "fusemap/common/math.h"
#include "fusemap/daemon/engine.h"
#include "fusemap/daemon/file_checkpointer.h"
#include "fusemap/daemon/resume.h"
#include "fusemap/io/lcm_conversions.h"
#include "fusemap/io/tum_trajectory.h"
#include "testing/null_publisher.h"
#include "testing/room_drive_log.h"
#include "testing/room_slam_config.h"
#include "testing/synthetic_room.h"

namespace fusemap {
namespace daemon {
namespace {

constexpr double kStepM = 0.15;
constexpr double kStartS = 1700000000.0;
constexpr char kYaml[] = "# the test's configuration text\n";


struct Message {
  std::string channel;
  std::vector<uint8_t> data;
};

// The room drive: loop closures happen after the resume point.
std::vector<Message> MakeLog() {
  std::vector<Message> log;
  for (auto& message : test_world::RoomDriveMessages(kStepM, kStartS, 7)) {
    log.push_back({message.channel, std::move(message.data)});
  }
  return log;
}

using test_world::NullPublisher;

// With checkpoint_period_s tiny the engine offers a save after every processed message; this
// one writes only after the `at_call`-th, i.e. after exactly that many queued messages.
class SaveAfterMessage : public Checkpointer {
 public:
  SaveAfterMessage(FileCheckpointer* file, int at_call) : file_(file), at_call_(at_call) {}
  bool Save(pose_graph::MapBuilder2D& builder, const RunRecord& record,
            std::string* error) override {
    return ++calls_ != at_call_ || file_->Save(builder, record, error);
  }

 private:
  FileCheckpointer* file_;
  const int at_call_;
  int calls_ = 0;
};

// Feeds log[begin, end) into a started engine; all are valid, so all are queued.
void Feed(Engine* engine, const std::vector<Message>& log, size_t begin, size_t end) {
  for (size_t i = begin; i < end; ++i) {
    ASSERT_TRUE(engine->intake().OnMessage(log[i].channel, log[i].data.data(),
                                           static_cast<int>(log[i].data.size())))
        << i;
  }
}

double Distance(const common::Rigid2d& a, const common::Rigid2d& b) {
  return (a.translation() - b.translation()).norm() +
         std::abs(common::NormalizeAngle(a.angle_rad() - b.angle_rad()));
}

// Resumes at the middle of the log; with replay_from_start the resumed engine is fed the whole
// log again (a file:// replay restarted), of which it must skip what the checkpoint holds.
void CheckResumedRunEqualsUninterruptedRun(bool replay_from_start) {
  const auto log = MakeLog();
  const io::SlamConfig config = test_world::RoomSlamConfig();
  RateLimitedLog quiet(1e9, [] { return 0.0; }, [](const std::string&) {});
  test_world::NullPublisher publisher;

  Engine whole(config, DaemonOptions(), 1, OverflowPolicy::kBlock, &publisher, &quiet);
  whole.Start();
  Feed(&whole, log, 0, log.size());
  whole.Finish();

  const std::string dir =
      ::testing::TempDir() + (replay_from_start ? "/resume_test_replay" : "/resume_test");
  std::filesystem::remove_all(dir);
  const size_t cut = log.size() / 2;
  {
    DaemonOptions options;
    options.checkpoint_period_s = 1e-9;
    FileCheckpointer file(CheckpointPath(dir), kYaml);
    SaveAfterMessage checkpointer(&file, static_cast<int>(cut));
    Engine first(config, options, 1, OverflowPolicy::kBlock, &publisher, &quiet);
    first.SetCheckpointer(&checkpointer);
    first.Start();
    Feed(&first, log, 0, cut);
    first.Finish();  // "killed": what it does after the checkpoint is never used
    ASSERT_EQ(file.stats().saved, 1);
    EXPECT_GT(file.stats().last_bytes, 1000);
    std::printf("checkpoint after %zu of %zu messages: %d nodes, %lld bytes, %.4f s\n", cut,
                log.size(), file.stats().last_nodes,
                static_cast<long long>(file.stats().last_bytes), file.stats().last_seconds);
  }

  ResumeCheckpoint checkpoint;
  std::string error;
  ASSERT_EQ(LoadResumeCheckpoint(CheckpointPath(dir), kYaml, &checkpoint, &error),
            ResumeStatus::kOk)
      << error;
  EXPECT_TRUE(checkpoint.warnings.empty());
  Engine resumed(config, DaemonOptions(), 1, OverflowPolicy::kBlock, &publisher, &quiet);
  resumed.Restore(checkpoint.contents.state, checkpoint.contents.odometry);
  resumed.Start();
  if (replay_from_start) {
    int skipped = 0;
    for (size_t i = 0; i < log.size(); ++i) {
      const bool queued = resumed.intake().OnMessage(log[i].channel, log[i].data.data(),
                                                     static_cast<int>(log[i].data.size()));
      skipped += !queued;
      if (i >= cut) {
        ASSERT_TRUE(queued) << i;
      }
    }
    EXPECT_EQ(skipped, static_cast<int>(cut));
    EXPECT_EQ(resumed.Health().time_resets, 0);
    for (const auto& channel : resumed.Health().channels) EXPECT_EQ(channel.malformed, 0);
  } else {
    Feed(&resumed, log, cut, log.size());
  }
  resumed.Finish();

  // The graph: every node of the whole run, where the uninterrupted run put it.
  const auto expected_nodes = whole.finished_builder().NodePoses();
  const auto nodes = resumed.finished_builder().NodePoses();
  ASSERT_EQ(nodes.size(), expected_nodes.size());
  ASSERT_GT(nodes.size(), checkpoint.contents.state.pose_graph.nodes.size() + 20);
  double max_node_error = 0.0;
  for (size_t i = 0; i < nodes.size(); ++i) {
    ASSERT_EQ(nodes[i].stamp_s, expected_nodes[i].stamp_s) << i;
    max_node_error = std::max(max_node_error, Distance(nodes[i].pose, expected_nodes[i].pose));
  }
  EXPECT_LT(max_node_error, 1e-9);
  EXPECT_EQ(resumed.finished_builder().pose_graph().stats().loop_closures_found,
            whole.finished_builder().pose_graph().stats().loop_closures_found);

  // trajectory.tum: the odometry record travels with the checkpoint, so the resumed run
  // densifies the whole span as the uninterrupted one (the TUM file keeps 1 µs and 1e-9).
  ASSERT_TRUE(resumed.WriteOutputs(dir, &error)) << error;
  eval::Trajectory written;
  ASSERT_TRUE(io::ReadTumTrajectoryFile(dir + "/trajectory.tum", &written, &error)) << error;
  const auto expected_dense =
      pose_graph::DensifyWithOdometry(expected_nodes, whole.odometry());
  ASSERT_GT(checkpoint.contents.odometry.size(), 50u);
  ASSERT_EQ(written.size(), session::ToTrajectory(expected_dense).size());
  double max_error = 0.0;
  size_t i = 0;
  for (const auto& pose : session::ToTrajectory(expected_dense)) {
    ASSERT_NEAR(written[i].stamp_s, pose.stamp_s, 1e-6) << i;
    max_error = std::max(max_error, Distance(written[i].pose.ToRigid2d(), pose.pose.ToRigid2d()));
    ++i;
  }
  EXPECT_LT(max_error, 1e-6);
}

TEST(ResumeTest, ResumedRunEqualsUninterruptedRunAndCoversItAll) {
  CheckResumedRunEqualsUninterruptedRun(false);
}

// Issue 18 item 10: --resume on a file:// replay mapped the log again from its start through a
// time reset (20 kill/resume cycles: 4,543 nodes and a 610 s trajectory instead of 942 / 300 s).
TEST(ResumeTest, ReplayFromTheStartSkipsWhatTheCheckpointHolds) {
  CheckResumedRunEqualsUninterruptedRun(true);
}

TEST(ResumeTest, CorruptCheckpointFallsBackToPreviousAndOtherVersionIsRefused) {
  const std::string dir = ::testing::TempDir() + "/resume_policy";
  std::filesystem::remove_all(dir);
  const auto log = MakeLog();
  common::InlineExecutor executor;
  pose_graph::MapBuilder2D builder(test_world::RoomSlamConfig().map_builder, &executor);
  FileCheckpointer file(CheckpointPath(dir), kYaml);
  std::string error;
  int fed = 0;
  auto feed_scans = [&](int scans) {
    for (int n = 0; n < scans;) {
      const auto& m = log[fed++];
      if (m.channel == "ODOMETRY") {
        sensor::OdometryData odometry;
        ASSERT_TRUE(io::DecodeOdometry(m.data.data(), static_cast<int>(m.data.size()), &odometry,
                                       &error));
        builder.AddOdometry(odometry);
        continue;
      }
      sensor::LaserScan scan;
      ASSERT_TRUE(io::DecodeLaserScan(m.data.data(), static_cast<int>(m.data.size()),
                                      test_world::RoomSlamConfig().lidar, &scan, &error));
      builder.AddScan(scan);
      ++n;
    }
  };
  feed_scans(10);
  ASSERT_TRUE(file.Save(builder, {}, &error)) << error;
  const size_t first_nodes = builder.NodePoses().size();
  feed_scans(10);
  ASSERT_TRUE(file.Save(builder, {}, &error)) << error;
  ASSERT_GT(builder.NodePoses().size(), first_nodes);

  ResumeCheckpoint good;
  ASSERT_EQ(LoadResumeCheckpoint(CheckpointPath(dir), kYaml, &good, &error), ResumeStatus::kOk);
  EXPECT_EQ(good.contents.state.pose_graph.nodes.size(), builder.NodePoses().size());
  EXPECT_TRUE(good.warnings.empty());

  // Truncated (a crash while copying it, a full disk): the previous one is used, with a reason.
  const auto size = std::filesystem::file_size(CheckpointPath(dir));
  std::filesystem::resize_file(CheckpointPath(dir), size / 2);
  ResumeCheckpoint fallback;
  ASSERT_EQ(LoadResumeCheckpoint(CheckpointPath(dir), kYaml, &fallback, &error),
            ResumeStatus::kOk)
      << error;
  EXPECT_EQ(fallback.used_path, CheckpointPath(dir) + ".prev");
  EXPECT_EQ(fallback.contents.state.pose_graph.nodes.size(), first_nodes);
  ASSERT_EQ(fallback.warnings.size(), 2u);
  EXPECT_NE(fallback.warnings[0].find(".prev"), std::string::npos) << fallback.warnings[0];
  // Set aside, so that the next save keeps the good one as .prev.
  EXPECT_FALSE(std::filesystem::exists(CheckpointPath(dir)));
  EXPECT_EQ(std::filesystem::file_size(CheckpointPath(dir) + ".rejected"), size / 2);
  ASSERT_TRUE(file.Save(builder, {}, &error)) << error;
  ResumeCheckpoint after_save;
  ASSERT_TRUE(io::ReadCheckpoint(CheckpointPath(dir) + ".prev", &after_save.contents, &error))
      << error;
  EXPECT_EQ(after_save.contents.state.pose_graph.nodes.size(), first_nodes);

  // Another configuration text: usable, with a warning.
  ResumeCheckpoint other_config;
  ASSERT_EQ(LoadResumeCheckpoint(CheckpointPath(dir), "other: 1\n", &other_config, &error),
            ResumeStatus::kOk);
  ASSERT_EQ(other_config.warnings.size(), 1u);
  EXPECT_NE(other_config.warnings[0].find("different configuration"), std::string::npos);

  // Both unreadable: refused.
  std::filesystem::resize_file(CheckpointPath(dir), 10);
  std::filesystem::resize_file(CheckpointPath(dir) + ".prev", 10);
  ResumeCheckpoint none;
  EXPECT_EQ(LoadResumeCheckpoint(CheckpointPath(dir), kYaml, &none, &error),
            ResumeStatus::kUnreadable);

  // Another fusemap version: refused, naming both versions.
  io::CheckpointContents foreign;
  foreign.fusemap_version = "0.0.0-other";
  foreign.options_yaml = kYaml;
  foreign.state = builder.ExportState();
  ASSERT_TRUE(io::WriteCheckpoint(CheckpointPath(dir), foreign, &error)) << error;
  ResumeCheckpoint refused;
  EXPECT_EQ(LoadResumeCheckpoint(CheckpointPath(dir), kYaml, &refused, &error),
            ResumeStatus::kVersionMismatch);
  EXPECT_NE(error.find("0.0.0-other"), std::string::npos) << error;
}

}  // namespace
}  // namespace daemon
}  // namespace fusemap
