#include "fusemap/io/trajectory_archive.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "fusemap/common/math.h"
#include "fusemap/io/run_outputs.h"

namespace fusemap {
namespace io {
namespace {

using TimedPose2d = pose_graph::MapBuilder2D::TimedPose2d;

// A curving drive: nodes every 0.7 s, odometry every 0.1 s that drifts from them, with a
// repeated stamp now and then (real logs have them).
struct DriveRun {
  std::vector<TimedPose2d> nodes;
  std::vector<sensor::OdometryData> odometry;
};

DriveRun MakeRun() {
  DriveRun run;
  for (int i = 0; i <= 300; ++i) {
    const double t = 0.1 * i;
    const common::Rigid2d truth({std::cos(0.1 * t) * 5.0, std::sin(0.1 * t) * 5.0}, 0.1 * t);
    run.odometry.push_back({t, common::Rigid2d(1.03 * truth.translation(), 1.05 * truth.angle_rad())});
    if (i % 37 == 5) run.odometry.push_back({t, run.odometry.back().pose});
    if (i % 7 == 3) run.nodes.push_back({t + 0.02, truth});
  }
  return run;
}

std::string TempDir(const std::string& name) {
  const std::string dir = ::testing::TempDir() + "/" + name;
  std::filesystem::remove_all(dir);
  return dir;
}

// Archives the nodes before each cut, with the odometry received by then, as the daemon does.
std::vector<sensor::OdometryData> ArchiveUpTo(const DriveRun& run, const std::vector<double>& cuts_s,
                                              size_t* nodes_archived, TrajectoryArchive* archive) {
  std::vector<sensor::OdometryData> record;
  size_t next_odometry = 0;
  *nodes_archived = 0;
  for (double cut_s : cuts_s) {
    while (next_odometry < run.odometry.size() && run.odometry[next_odometry].stamp_s <= cut_s) {
      record.push_back(run.odometry[next_odometry++]);
    }
    std::vector<pose_graph::ArchivedNode2D> nodes;
    while (*nodes_archived < run.nodes.size() && run.nodes[*nodes_archived].stamp_s < cut_s - 1.0) {
      nodes.push_back({run.nodes[*nodes_archived].stamp_s, run.nodes[*nodes_archived].pose});
      ++*nodes_archived;
    }
    std::string error;
    EXPECT_TRUE(archive->Append(nodes, &record, &error)) << error;
  }
  record.insert(record.end(), run.odometry.begin() + next_odometry, run.odometry.end());
  return record;
}

void ExpectSameTrajectory(const eval::Trajectory& expected, const eval::Trajectory& actual) {
  ASSERT_EQ(actual.size(), expected.size());
  for (size_t i = 0; i < actual.size(); ++i) {
    ASSERT_NEAR(actual[i].stamp_s, expected[i].stamp_s, 1e-6) << i;
    // The archived part went through the TUM text (1e-9).
    EXPECT_LT((actual[i].pose.translation() - expected[i].pose.translation()).norm(), 1e-8) << i;
    EXPECT_LT(std::abs(common::NormalizeAngle(actual[i].pose.ToRigid2d().angle_rad() -
                                              expected[i].pose.ToRigid2d().angle_rad())),
              1e-8)
        << i;
  }
}

TEST(TrajectoryArchiveTest, ArchivedPiecesAndTheRestAreTheWholeRunDensified) {
  const DriveRun run = MakeRun();
  std::string error, warning;
  auto archive = TrajectoryArchive::Open(TempDir("archive_whole"), nullptr, &warning, &error);
  ASSERT_NE(archive, nullptr) << error;
  size_t archived = 0;
  const auto record = ArchiveUpTo(run, {3.0, 3.05, 9.0, 17.3, 24.0}, &archived, archive.get());
  ASSERT_GT(archived, 20u);
  // The record keeps only what the graph's nodes still need.
  EXPECT_LT(record.size(), run.odometry.size() / 2);
  EXPECT_GT(archive->mark().trajectory_bytes, 1000u);

  const std::vector<TimedPose2d> kept(run.nodes.begin() + archived, run.nodes.end());
  eval::Trajectory trajectory, nodes, odometry;
  ASSERT_TRUE(archive->ReadWholeRun(kept, record, &trajectory, &nodes, &odometry, &error)) << error;
  ExpectSameTrajectory(ToTrajectory(pose_graph::DensifyWithOdometry(run.nodes, run.odometry)),
                       trajectory);
  ExpectSameTrajectory(ToTrajectory(run.nodes), nodes);
  std::vector<TimedPose2d> raw;
  for (const auto& o : run.odometry) raw.push_back({o.stamp_s, o.pose});
  ExpectSameTrajectory(ToTrajectory(raw), odometry);
}

TEST(TrajectoryArchiveTest, ResumeCutsTheFilesBackToTheCheckpointsMark) {
  const DriveRun run = MakeRun();
  const std::string dir = TempDir("archive_resume");
  std::string error, warning;
  TrajectoryArchiveMark mark;
  std::vector<sensor::OdometryData> record_at_mark;
  size_t archived_at_mark = 0;
  {
    auto archive = TrajectoryArchive::Open(dir, nullptr, &warning, &error);
    ASSERT_NE(archive, nullptr) << error;
    record_at_mark = ArchiveUpTo(run, {6.0, 12.0}, &archived_at_mark, archive.get());
    mark = archive->mark();
    // Appends after the checkpoint, then a crash.
    std::vector<sensor::OdometryData> later = record_at_mark;
    std::vector<pose_graph::ArchivedNode2D> more;
    for (size_t i = archived_at_mark; i < archived_at_mark + 5; ++i) {
      more.push_back({run.nodes[i].stamp_s, run.nodes[i].pose});
    }
    ASSERT_TRUE(archive->Append(more, &later, &error)) << error;
    ASSERT_GT(archive->mark().nodes_bytes, mark.nodes_bytes);
  }
  auto resumed = TrajectoryArchive::Open(dir, &mark, &warning, &error);
  ASSERT_NE(resumed, nullptr) << error;
  EXPECT_TRUE(warning.empty()) << warning;
  EXPECT_EQ(std::filesystem::file_size(dir + "/nodes.tum"), mark.nodes_bytes);
  const std::vector<TimedPose2d> kept(run.nodes.begin() + archived_at_mark, run.nodes.end());
  eval::Trajectory trajectory, nodes, odometry;
  ASSERT_TRUE(resumed->ReadWholeRun(kept, record_at_mark, &trajectory, &nodes, &odometry, &error))
      << error;
  ExpectSameTrajectory(ToTrajectory(run.nodes), nodes);
  ExpectSameTrajectory(ToTrajectory(pose_graph::DensifyWithOdometry(run.nodes, run.odometry)),
                       trajectory);

  // An archive shorter than the checkpoint says is not the checkpoint's: it starts over from
  // the mark, so mapping goes on and the outputs begin after the lost part.
  resumed.reset();
  std::filesystem::resize_file(dir + "/trajectory.tum", mark.trajectory_bytes / 2);
  auto restarted = TrajectoryArchive::Open(dir, &mark, &warning, &error);
  ASSERT_NE(restarted, nullptr) << error;
  EXPECT_NE(warning.find("trajectory.tum"), std::string::npos) << warning;
  EXPECT_NE(warning.find("starts over"), std::string::npos) << warning;
  EXPECT_EQ(restarted->mark().nodes_bytes, 0u);
  EXPECT_EQ(std::filesystem::file_size(dir + "/nodes.tum"), 0u);
  ASSERT_TRUE(restarted->ReadWholeRun(kept, record_at_mark, &trajectory, &nodes, &odometry, &error))
      << error;
  ASSERT_FALSE(trajectory.empty());
  EXPECT_GT(trajectory.front().stamp_s, mark.last_output_stamp_s);
  EXPECT_EQ(nodes.size(), kept.size());
}

TEST(TrajectoryArchiveTest, NothingToArchiveWritesNothing) {
  std::string error, warning;
  auto archive = TrajectoryArchive::Open(TempDir("archive_empty"), nullptr, &warning, &error);
  ASSERT_NE(archive, nullptr) << error;
  std::vector<sensor::OdometryData> record = {{1.0, common::Rigid2d::Identity()}};
  ASSERT_TRUE(archive->Append({}, &record, &error)) << error;
  EXPECT_EQ(record.size(), 1u);
  EXPECT_EQ(archive->mark().trajectory_bytes, 0u);
  EXPECT_FALSE(archive->mark().has_last_node);
}

}  // namespace
}  // namespace io
}  // namespace fusemap
