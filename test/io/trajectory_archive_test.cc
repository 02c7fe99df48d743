#include "fusemap/io/trajectory_archive.h"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <csignal>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fusemap {
namespace io {
namespace {

using TimedPose2d = pose_graph::MapBuilder2D::TimedPose2d;

// A curving drive: a node every 0.7 s, odometry every 0.1 s.
struct DriveRun {
  std::vector<TimedPose2d> nodes;
  std::vector<sensor::OdometryData> odometry;
};

DriveRun MakeRun() {
  DriveRun run;
  for (int i = 0; i <= 300; ++i) {
    const double t = 0.1 * i;
    const common::Rigid2d pose({std::cos(0.1 * t) * 5.0, std::sin(0.1 * t) * 5.0}, 0.1 * t + 0.3);
    run.odometry.push_back({t, pose});
    if (i % 7 == 3) run.nodes.push_back({t + 0.02, pose});
  }
  return run;
}

std::string TempDir(const std::string& name) {
  const std::string dir = ::testing::TempDir() + "/" + name;
  std::filesystem::remove_all(dir);
  return dir;
}

// As the daemon does at each checkpoint: every `period` nodes, hands over the nodes at odd
// positions (trimming leaves holes, it does not eat the graph from the front) and the odometry
// received so far. Returns the nodes kept and the record since the last append.
void ArchiveInSteps(const DriveRun& run, size_t period, TrajectoryArchive* archive,
                    std::vector<TimedPose2d>* kept, std::vector<sensor::OdometryData>* record) {
  size_t next_odometry = 0;
  for (size_t begin = 0; begin < run.nodes.size(); begin += period) {
    std::vector<pose_graph::ArchivedNode2D> taken;
    for (size_t n = begin; n < std::min(run.nodes.size(), begin + period); ++n) {
      if (n % 2 == 1) {
        taken.push_back({static_cast<int>(n), run.nodes[n].stamp_s, run.nodes[n].pose});
      } else {
        kept->push_back(run.nodes[n]);
      }
    }
    const double until_s = run.nodes[std::min(run.nodes.size(), begin + period) - 1].stamp_s;
    while (next_odometry < run.odometry.size() && run.odometry[next_odometry].stamp_s <= until_s) {
      record->push_back(run.odometry[next_odometry++]);
    }
    std::string error;
    ASSERT_TRUE(archive->Append(taken, record, &error)) << error;
    EXPECT_TRUE(record->empty());
  }
  record->assign(run.odometry.begin() + next_odometry, run.odometry.end());
}

void ExpectBitForBit(const std::vector<TimedPose2d>& expected,
                     const std::vector<TimedPose2d>& actual) {
  ASSERT_EQ(actual.size(), expected.size());
  for (size_t i = 0; i < actual.size(); ++i) {
    EXPECT_EQ(actual[i].stamp_s, expected[i].stamp_s) << i;
    EXPECT_EQ(actual[i].pose.translation(), expected[i].pose.translation()) << i;
    EXPECT_EQ(actual[i].pose.angle_rad(), expected[i].pose.angle_rad()) << i;
  }
}

void ExpectBitForBit(const std::vector<sensor::OdometryData>& expected,
                     const std::vector<sensor::OdometryData>& actual) {
  std::vector<TimedPose2d> a, b;
  for (const auto& o : expected) a.push_back({o.stamp_s, o.pose});
  for (const auto& o : actual) b.push_back({o.stamp_s, o.pose});
  ExpectBitForBit(a, b);
}

TEST(TrajectoryArchiveTest, WholeRunComesBackBitForBit) {
  const DriveRun run = MakeRun();
  std::string error, warning;
  auto archive = TrajectoryArchive::Open(TempDir("archive_whole"), nullptr, &warning, &error);
  ASSERT_NE(archive, nullptr) << error;
  std::vector<TimedPose2d> kept;
  std::vector<sensor::OdometryData> record;
  ArchiveInSteps(run, 6, archive.get(), &kept, &record);
  EXPECT_EQ(archive->mark().nodes_bytes, 36u * (run.nodes.size() - kept.size()));
  EXPECT_GT(archive->mark().odometry_bytes, 32u * 250);
  EXPECT_LT(record.size(), 40u);

  std::vector<TimedPose2d> nodes;
  std::vector<sensor::OdometryData> odometry;
  ASSERT_TRUE(archive->ReadWholeRun(kept, record, &nodes, &odometry, &error)) << error;
  ExpectBitForBit(run.nodes, nodes);
  ExpectBitForBit(run.odometry, odometry);
}

TEST(TrajectoryArchiveTest, ResumeCutsTheFilesBackToTheCheckpointsMark) {
  const DriveRun run = MakeRun();
  const std::string dir = TempDir("archive_resume");
  std::string error, warning;
  TrajectoryArchiveMark mark;
  {
    auto archive = TrajectoryArchive::Open(dir, nullptr, &warning, &error);
    ASSERT_NE(archive, nullptr) << error;
    std::vector<sensor::OdometryData> record(run.odometry.begin(), run.odometry.begin() + 100);
    ASSERT_TRUE(archive->Append({{0, run.nodes[0].stamp_s, run.nodes[0].pose}}, &record, &error));
    mark = archive->mark();
    // Appended after that checkpoint, then a crash.
    record.assign(run.odometry.begin() + 100, run.odometry.begin() + 150);
    ASSERT_TRUE(archive->Append({{1, run.nodes[1].stamp_s, run.nodes[1].pose}}, &record, &error));
  }
  EXPECT_EQ(mark.last_odometry_stamp_s, run.odometry[99].stamp_s);
  auto resumed = TrajectoryArchive::Open(dir, &mark, &warning, &error);
  ASSERT_NE(resumed, nullptr) << error;
  EXPECT_TRUE(warning.empty()) << warning;
  EXPECT_EQ(std::filesystem::file_size(dir + "/nodes.bin"), 36u);
  EXPECT_EQ(std::filesystem::file_size(dir + "/odometry.bin"), 3200u);
  const std::vector<TimedPose2d> kept(run.nodes.begin() + 1, run.nodes.end());
  const std::vector<sensor::OdometryData> rest(run.odometry.begin() + 100, run.odometry.end());
  std::vector<TimedPose2d> nodes;
  std::vector<sensor::OdometryData> odometry;
  ASSERT_TRUE(resumed->ReadWholeRun(kept, rest, &nodes, &odometry, &error)) << error;
  ExpectBitForBit(run.nodes, nodes);
  ExpectBitForBit(run.odometry, odometry);

  // An archive shorter than the checkpoint says is not the checkpoint's: it starts over, so
  // mapping goes on and only the lost part is missing from the outputs.
  resumed.reset();
  std::filesystem::resize_file(dir + "/odometry.bin", 1000);
  auto restarted = TrajectoryArchive::Open(dir, &mark, &warning, &error);
  ASSERT_NE(restarted, nullptr) << error;
  EXPECT_NE(warning.find("odometry.bin"), std::string::npos) << warning;
  EXPECT_NE(warning.find("starts over"), std::string::npos) << warning;
  EXPECT_EQ(restarted->mark().nodes_bytes, 0u);
  EXPECT_EQ(std::filesystem::file_size(dir + "/nodes.bin"), 0u);
  ASSERT_TRUE(restarted->ReadWholeRun(kept, rest, &nodes, &odometry, &error)) << error;
  EXPECT_EQ(nodes.size(), kept.size());
  EXPECT_EQ(odometry.size(), rest.size());
}

TEST(TrajectoryArchiveTest, DamagedFilesAreErrorsNamingTheFile) {
  const DriveRun run = MakeRun();
  const std::string dir = TempDir("archive_damaged");
  std::string error, warning;
  auto archive = TrajectoryArchive::Open(dir, nullptr, &warning, &error);
  ASSERT_NE(archive, nullptr) << error;
  std::vector<sensor::OdometryData> record(run.odometry.begin(), run.odometry.begin() + 3);
  ASSERT_TRUE(archive->Append({}, &record, &error)) << error;
  // A NaN where a stamp was (bytes 32..39: the second sample's stamp).
  {
    std::fstream file(dir + "/odometry.bin", std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(32);
    const double nan = std::nan("");
    file.write(reinterpret_cast<const char*>(&nan), sizeof(nan));
  }
  std::vector<TimedPose2d> nodes;
  std::vector<sensor::OdometryData> odometry;
  EXPECT_FALSE(archive->ReadWholeRun({}, {}, &nodes, &odometry, &error));
  EXPECT_NE(error.find("odometry.bin"), std::string::npos) << error;
  EXPECT_NE(error.find("not finite"), std::string::npos) << error;
}

// A full disk, played by a file size limit: the failed append leaves files, mark and record as
// they were, and the same append goes through once there is room.
TEST(TrajectoryArchiveTest, FailedAppendChangesNothingAndCanBeRetried) {
  const DriveRun run = MakeRun();
  const std::string dir = TempDir("archive_full");
  std::string error, warning;
  auto archive = TrajectoryArchive::Open(dir, nullptr, &warning, &error);
  ASSERT_NE(archive, nullptr) << error;
  std::vector<sensor::OdometryData> record(run.odometry.begin(), run.odometry.begin() + 10);
  ASSERT_TRUE(archive->Append({{0, run.nodes[0].stamp_s, run.nodes[0].pose}}, &record, &error));
  const TrajectoryArchiveMark before = archive->mark();

  record.assign(run.odometry.begin() + 10, run.odometry.begin() + 200);
  const std::vector<pose_graph::ArchivedNode2D> nodes = {
      {1, run.nodes[1].stamp_s, run.nodes[1].pose}};
  std::signal(SIGXFSZ, SIG_IGN);
  rlimit saved{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &saved), 0);
  rlimit small = saved;
  small.rlim_cur = before.odometry_bytes + 1000;  // room for the node, not for 190 samples
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
  const bool appended = archive->Append(nodes, &record, &error);
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &saved), 0);
  EXPECT_FALSE(appended);
  EXPECT_NE(error.find("odometry.bin"), std::string::npos) << error;
  EXPECT_EQ(archive->mark().nodes_bytes, before.nodes_bytes);
  EXPECT_EQ(archive->mark().odometry_bytes, before.odometry_bytes);
  EXPECT_EQ(std::filesystem::file_size(dir + "/nodes.bin"), before.nodes_bytes);
  EXPECT_EQ(std::filesystem::file_size(dir + "/odometry.bin"), before.odometry_bytes);
  EXPECT_EQ(record.size(), 190u);

  ASSERT_TRUE(archive->Append(nodes, &record, &error)) << error;
  std::vector<TimedPose2d> all_nodes;
  std::vector<sensor::OdometryData> all_odometry;
  ASSERT_TRUE(archive->ReadWholeRun({}, {}, &all_nodes, &all_odometry, &error)) << error;
  ExpectBitForBit(std::vector<TimedPose2d>(run.nodes.begin(), run.nodes.begin() + 2), all_nodes);
  ExpectBitForBit(std::vector<sensor::OdometryData>(run.odometry.begin(), run.odometry.begin() + 200),
                  all_odometry);
}

}  // namespace
}  // namespace io
}  // namespace fusemap
