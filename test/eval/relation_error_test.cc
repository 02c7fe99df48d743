#include "fusemap/eval/relation_error.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fusemap {
namespace eval {
namespace {

// A curvy planar path sampled at 10 Hz: T_world_body(t).
common::Rigid2d PathPose(double t) {
  return common::Rigid2d(2.0 * std::sin(0.1 * t) + 0.3 * t, std::cos(0.13 * t),
                         0.4 * std::sin(0.2 * t));
}

Trajectory SamplePath(double t_end, double dt) {
  Trajectory trajectory;
  for (double t = 0.0; t <= t_end + 1e-9; t += dt) {
    trajectory.push_back(TimedPose3d{t, common::Rigid3d::FromRigid2d(PathPose(t))});
  }
  return trajectory;
}

std::vector<Relation> TrueRelations(const std::vector<std::pair<double, double>>& stamps) {
  std::vector<Relation> relations;
  for (const auto& [t1, t2] : stamps) {
    relations.push_back(Relation{t1, t2, PathPose(t1).inverse() * PathPose(t2)});
  }
  return relations;
}

TEST(RelationErrorTest, PerfectTrajectoryHasZeroError) {
  const Trajectory est = SamplePath(20.0, 0.1);
  const RelationError r =
      EvaluateRelations(est, TrueRelations({{1.0, 2.0}, {3.5, 9.2}, {0.0, 20.0}}));
  EXPECT_EQ(r.count_used, 3);
  EXPECT_EQ(r.count_skipped, 0);
  EXPECT_NEAR(r.trans_m.mean, 0.0, 1e-9);
  EXPECT_NEAR(r.rot_deg.mean, 0.0, 1e-9);
  EXPECT_NEAR(r.trans_sq_m2.mean, 0.0, 1e-12);
}

TEST(RelationErrorTest, ConstantBiasGivesMeanEqualToBias) {
  const Trajectory est = SamplePath(20.0, 0.1);
  // The true relation is the estimated motion with a bias removed: E = bias^-1 exactly.
  const common::Rigid2d bias(0.03, -0.04, common::DegToRad(2.0));
  std::vector<Relation> relations = TrueRelations({{1.0, 2.0}, {3.0, 7.0}, {10.0, 15.5}});
  for (Relation& relation : relations) relation.T_1_2 = relation.T_1_2 * bias;
  const RelationError r = EvaluateRelations(est, relations);
  ASSERT_EQ(r.count_used, 3);
  EXPECT_NEAR(r.trans_m.mean, 0.05, 1e-9);
  EXPECT_NEAR(r.trans_m.std, 0.0, 1e-9);
  EXPECT_NEAR(r.rot_deg.mean, 2.0, 1e-9);
  EXPECT_NEAR(r.trans_sq_m2.mean, 0.0025, 1e-11);
  EXPECT_NEAR(r.rot_sq_deg2.mean, 4.0, 1e-8);
}

TEST(RelationErrorTest, MeanAndStdOfTwoDifferentErrors) {
  const Trajectory est = SamplePath(10.0, 0.1);
  std::vector<Relation> relations = TrueRelations({{1.0, 2.0}, {3.0, 4.0}});
  relations[0].T_1_2 = relations[0].T_1_2 * common::Rigid2d(0.1, 0.0, 0.0);
  relations[1].T_1_2 = relations[1].T_1_2 * common::Rigid2d(0.0, 0.3, 0.0);
  const RelationError r = EvaluateRelations(est, relations);
  EXPECT_NEAR(r.trans_m.mean, 0.2, 1e-9);
  EXPECT_NEAR(r.trans_m.std, 0.1, 1e-9);  // Population std.
  EXPECT_NEAR(r.trans_sq_m2.mean, 0.05, 1e-9);
  EXPECT_NEAR(r.trans_sq_m2.std, 0.04, 1e-9);
}

TEST(RelationErrorTest, SkipsRelationsOutsideTrajectory) {
  const Trajectory est = SamplePath(10.0, 0.1);
  const RelationError r =
      EvaluateRelations(est, TrueRelations({{1.0, 2.0}, {9.0, 10.2}, {-0.2, 3.0}}), 0.05);
  EXPECT_EQ(r.count_used, 1);
  EXPECT_EQ(r.count_skipped, 2);
}

TEST(RelationErrorTest, InterpolatesBetweenSamples) {
  // A straight line at 1 m/s sampled at 1 Hz: a relation between mid-sample stamps is
  // exact only with interpolation (nearest-sample would be 1 m off).
  Trajectory est;
  for (int i = 0; i <= 10; ++i) {
    est.push_back(
        TimedPose3d{double(i), common::Rigid3d::FromRigid2d(common::Rigid2d(i, 0.0, 0.0))});
  }
  const Relation relation{2.5, 5.25, common::Rigid2d(2.75, 0.0, 0.0)};
  const RelationError r = EvaluateRelations(est, {relation}, 0.6);
  ASSERT_EQ(r.count_used, 1);
  EXPECT_NEAR(r.trans_m.mean, 0.0, 1e-9);
  // With a tighter gap than the distance to the nearest sample the relation is skipped.
  EXPECT_EQ(EvaluateRelations(est, {relation}, 0.2).count_skipped, 1);
}

TEST(RelationErrorTest, RotationErrorWrapsAroundPi) {
  Trajectory est;
  est.push_back(TimedPose3d{0.0, common::Rigid3d::FromRigid2d(common::Rigid2d(0, 0, 0))});
  est.push_back(TimedPose3d{1.0, common::Rigid3d::FromRigid2d(common::Rigid2d(0, 0, 3.13))});
  const RelationError r =
      EvaluateRelations(est, {Relation{0.0, 1.0, common::Rigid2d(0, 0, -3.13)}});
  EXPECT_NEAR(r.rot_deg.mean, common::RadToDeg(2.0 * common::kPi - 6.26), 1e-9);
}

}  // namespace
}  // namespace eval
}  // namespace fusemap
