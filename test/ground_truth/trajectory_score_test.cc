#include "fusemap/ground_truth/trajectory_score.h"

#include <gtest/gtest.h>

namespace fusemap {
namespace ground_truth {
namespace {

using common::Rigid3d;

// A 4 m x 4 m square driven at 0.5 m/s, sampled at 10 Hz, ending where it started.
eval::Trajectory SquareLoop() {
  eval::Trajectory trajectory;
  const Eigen::Vector2d corners[] = {{0, 0}, {4, 0}, {4, 4}, {0, 4}, {0, 0}};
  double t = 100.0;
  for (int side = 0; side < 4; ++side) {
    const Eigen::Vector2d a = corners[side], b = corners[side + 1];
    const double yaw = std::atan2(b.y() - a.y(), b.x() - a.x());
    for (int i = 0; i < 80; ++i) {
      const Eigen::Vector2d p = a + (b - a) * (i / 80.0);
      trajectory.push_back({t, Rigid3d::FromRigid2d(common::Rigid2d(p, yaw))});
      t += 0.1;
    }
  }
  trajectory.push_back({t, Rigid3d::FromRigid2d(common::Rigid2d(corners[4], 0.0))});
  return trajectory;
}

eval::Trajectory Transformed(const eval::Trajectory& in, const Rigid3d& T) {
  eval::Trajectory out = in;
  for (auto& p : out) p.pose = T * p.pose;
  return out;
}

TEST(TrajectoryScoreTest, RigidlyMovedCopyScoresZeroAfterAlignment) {
  const eval::Trajectory gt = SquareLoop();
  const Rigid3d T(Eigen::Vector3d(1.0, -2.0, 0.0),
                  Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ())));
  TrajectoryScore score;
  std::string error;
  ASSERT_TRUE(ScoreTrajectory(gt, Transformed(gt, T), {}, {}, ScoreOptions(), &score, &error))
      << error;
  EXPECT_EQ(score.associated, static_cast<int>(gt.size()));
  EXPECT_NEAR(score.gt_length_m, 16.0, 1e-9);
  EXPECT_LT(score.ate.trans_m.rmse, 1e-9);
  EXPECT_GT(score.ate.unaligned_rmse_m, 1.0);
  EXPECT_LT(score.rpe_trans_per_m, 1e-9);
  EXPECT_GT(score.rpe.trans_m.count, 0);
  ASSERT_TRUE(score.has_loop);
  EXPECT_NEAR(score.loop_end_s, gt.back().stamp_s, 1e-9);
  EXPECT_LT(score.loop_error_m, 1e-9);
}

TEST(TrajectoryScoreTest, TranslatedCopyHasUnalignedErrorOfTheOffset) {
  const eval::Trajectory gt = SquareLoop();
  const Rigid3d T(Eigen::Vector3d(0.3, 0.4, 0.0), Eigen::Quaterniond::Identity());
  TrajectoryScore score;
  std::string error;
  ASSERT_TRUE(ScoreTrajectory(gt, Transformed(gt, T), {}, {}, ScoreOptions(), &score, &error));
  EXPECT_NEAR(score.ate.unaligned_rmse_m, 0.5, 1e-9);
  EXPECT_LT(score.ate.trans_m.rmse, 1e-9);
}

// Only the closing pose is off by 0.2 m: the loop error shows it (the alignment, fitted to all
// 321 poses, barely moves).
TEST(TrajectoryScoreTest, LoopErrorIsTheClosingOffset) {
  const eval::Trajectory gt = SquareLoop();
  eval::Trajectory est = gt;
  est.back().pose =
      Rigid3d(Eigen::Vector3d(0.0, 0.2, 0.0), Eigen::Quaterniond::Identity()) * est.back().pose;
  TrajectoryScore score;
  std::string error;
  ASSERT_TRUE(ScoreTrajectory(gt, est, {}, {}, ScoreOptions(), &score, &error));
  ASSERT_TRUE(score.has_loop);
  EXPECT_NEAR(score.loop_error_m, 0.2, 0.005);
  EXPECT_NEAR(score.ate.trans_m.max, 0.2, 0.005);
}

TEST(TrajectoryScoreTest, OpenPathHasNoLoop) {
  eval::Trajectory gt = SquareLoop();
  gt.resize(200);  // Stops half-way round.
  TrajectoryScore score;
  std::string error;
  ASSERT_TRUE(ScoreTrajectory(gt, gt, {}, {}, ScoreOptions(), &score, &error));
  EXPECT_FALSE(score.has_loop);
}

TEST(TrajectoryScoreTest, TagResidualsAndMeasures) {
  const eval::Trajectory gt = SquareLoop();
  std::vector<TagSighting> sightings;
  for (size_t i = 0; i < gt.size(); i += 40) {
    const double offset_m = (i / 40) % 2 == 0 ? 0.05 : 0.0;  // Tag 5 is surveyed 5 cm off.
    const int id = offset_m > 0.0 ? 5 : 6;
    sightings.push_back(
        {gt[i].stamp_s, id,
         Rigid3d(Eigen::Vector3d(offset_m, 0, 0), Eigen::Quaterniond::Identity()) * gt[i].pose});
  }
  MapMeasure measure;
  measure.from = "door";
  measure.to = "pillar";
  measure.measured_m = 5.0;
  measure.from_map = {1.0, 1.0};
  measure.to_map = {4.0, 5.02};
  TrajectoryScore score;
  std::string error;
  ASSERT_TRUE(ScoreTrajectory(gt, gt, sightings, {measure}, ScoreOptions(), &score, &error));
  ASSERT_EQ(score.tag_residuals.size(), 2u);
  EXPECT_EQ(score.tag_residuals[0].tag_id, 5);
  EXPECT_NEAR(score.tag_residuals[0].position_error_m.mean, 0.05, 1e-9);
  EXPECT_EQ(score.tag_residuals[0].position_error_m.count, 5);
  EXPECT_NEAR(score.tag_residuals[1].position_error_m.max, 0.0, 1e-9);
  ASSERT_EQ(score.measures.size(), 1u);
  EXPECT_NEAR(score.measures[0].map_m, std::hypot(3.0, 4.02), 1e-12);
  EXPECT_NEAR(score.measures[0].error_m, std::hypot(3.0, 4.02) - 5.0, 1e-12);
}

TEST(TrajectoryScoreTest, DisjointTimesAreAnError) {
  const eval::Trajectory gt = SquareLoop();
  eval::Trajectory est = gt;
  for (auto& p : est) p.stamp_s += 1000.0;
  TrajectoryScore score;
  std::string error;
  EXPECT_FALSE(ScoreTrajectory(gt, est, {}, {}, ScoreOptions(), &score, &error));
  EXPECT_NE(error.find("no estimated pose"), std::string::npos) << error;
}

// Issue 16: config/tagscore.yaml's score: keys are reported by name and line.
TEST(TrajectoryScoreTest, BadOptionNamesItsKeyAndLine) {
  std::string error;
  auto reader = common::ConfigReader::FromString("max_time_diff_s: 0.1\nloop_radius_m: 0\n",
                                                 "score.yaml", &error);
  ASSERT_NE(reader, nullptr) << error;
  ParseScoreOptions(*reader);
  EXPECT_FALSE(reader->Finish(&error));
  EXPECT_EQ(error, "score.yaml:2: key 'loop_radius_m': must be > 0");
}

}  // namespace
}  // namespace ground_truth
}  // namespace fusemap
