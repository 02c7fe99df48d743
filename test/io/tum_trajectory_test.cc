#include "fusemap/io/tum_trajectory.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <sstream>

namespace fusemap {
namespace io {
namespace {

bool Read(const std::string& text, eval::Trajectory* trajectory, std::string* error) {
  std::istringstream in(text);
  return ReadTumTrajectory(in, "traj.tum", trajectory, error);
}

std::string ReadError(const std::string& text) {
  eval::Trajectory trajectory;
  std::string error;
  EXPECT_FALSE(Read(text, &trajectory, &error)) << text;
  return error;
}

TEST(TumTrajectoryTest, ParsesCommentsBlankLinesAndNormalisesQuaternion) {
  eval::Trajectory trajectory;
  std::string error;
  ASSERT_TRUE(Read("# header\n\n1.5 1 2 3 0 0 0 2\n  # indented comment\n2.0 4 5 6 0 0 1 1\r\n",
                   &trajectory, &error))
      << error;
  ASSERT_EQ(trajectory.size(), 2u);
  EXPECT_DOUBLE_EQ(trajectory[0].stamp_s, 1.5);
  EXPECT_EQ(trajectory[0].pose.translation(), Eigen::Vector3d(1, 2, 3));
  EXPECT_NEAR(trajectory[0].pose.rotation().w(), 1.0, 1e-12);
  EXPECT_NEAR(trajectory[1].pose.rotation().z(), std::sqrt(0.5), 1e-12);
}

TEST(TumTrajectoryTest, ErrorsNameFileAndLine) {
  EXPECT_EQ(ReadError("1 2 3 4 0 0 0\n"),
            "traj.tum:1: expected 8 fields 't x y z qx qy qz qw', got 7");
  EXPECT_EQ(ReadError("# c\n1 2 3 4 0 0 0 1 9\n"), "traj.tum:2: more than 8 fields");
  EXPECT_EQ(ReadError("1 2 x 4 0 0 0 1\n"), "traj.tum:1: field 3 'x' is not a number");
  EXPECT_EQ(ReadError("1 2 3abc 4 0 0 0 1\n"), "traj.tum:1: field 3 '3abc' is not a number");
  EXPECT_EQ(ReadError("1 2 nan 4 0 0 0 1\n"), "traj.tum:1: field 3 is not finite");
  EXPECT_EQ(ReadError("1 2 3 4 0 0 0 0\n"), "traj.tum:1: quaternion has zero norm");
  EXPECT_EQ(ReadError("2 0 0 0 0 0 0 1\n\n1 0 0 0 0 0 0 1\n"),
            "traj.tum:3: time 1.000000 does not increase (previous pose at 2.000000)");
  EXPECT_EQ(ReadError("1 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n").substr(0, 11), "traj.tum:2:");
}

TEST(TumTrajectoryTest, WriteReadRoundTrip) {
  eval::Trajectory written;
  for (int i = 0; i < 20; ++i) {
    const Eigen::Quaterniond q(
        Eigen::AngleAxisd(0.3 * i - 2.0, Eigen::Vector3d(1, 2, 3).normalized()));
    written.push_back(eval::TimedPose3d{
        976052857.337284 + 0.2 * i, common::Rigid3d(Eigen::Vector3d(i, -0.5 * i, 1e-3 * i), q)});
  }
  char dir_template[] = "/tmp/fusemap_tum_XXXXXX";
  ASSERT_NE(mkdtemp(dir_template), nullptr);
  const std::string path = std::string(dir_template) + "/t.tum";
  std::string error;
  ASSERT_TRUE(WriteTumTrajectoryFile(path, written, &error)) << error;
  eval::Trajectory read;
  ASSERT_TRUE(ReadTumTrajectoryFile(path, &read, &error)) << error;
  ASSERT_EQ(read.size(), written.size());
  for (size_t i = 0; i < read.size(); ++i) {
    EXPECT_NEAR(read[i].stamp_s, written[i].stamp_s, 1e-6);
    EXPECT_NEAR((read[i].pose.translation() - written[i].pose.translation()).norm(), 0.0, 1e-8);
    EXPECT_NEAR(read[i].pose.rotation().angularDistance(written[i].pose.rotation()), 0.0, 1e-8);
  }
  std::remove(path.c_str());
  rmdir(dir_template);
}

TEST(TumTrajectoryTest, MissingFileAndUnwritablePath) {
  eval::Trajectory trajectory;
  std::string error;
  EXPECT_FALSE(ReadTumTrajectoryFile("/nonexistent/x.tum", &trajectory, &error));
  EXPECT_EQ(error, "/nonexistent/x.tum: cannot open for reading");
  EXPECT_FALSE(WriteTumTrajectoryFile("/nonexistent/x.tum", trajectory, &error));
  EXPECT_EQ(error, "/nonexistent/x.tum: cannot open /nonexistent/x.tum.tmp for writing: No such "
                   "file or directory");
}

}  // namespace
}  // namespace io
}  // namespace fusemap
