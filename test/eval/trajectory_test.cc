#include "fusemap/eval/trajectory.h"

#include <gtest/gtest.h>

namespace fusemap {
namespace eval {
namespace {

Trajectory Line() {
  Trajectory t;
  for (int i = 0; i < 5; ++i) {
    t.push_back(TimedPose3d{0.5 * i, common::Rigid3d(Eigen::Vector3d(i, 2.0 * i, 0.0),
                                                     Eigen::Quaterniond::Identity())});
  }
  return t;
}

TEST(TrajectoryTest, IsStrictlyIncreasing) {
  Trajectory t = Line();
  EXPECT_TRUE(IsStrictlyIncreasing(t));
  t[2].stamp_s = t[1].stamp_s;
  EXPECT_FALSE(IsStrictlyIncreasing(t));
}

TEST(TrajectoryTest, LookUpExactInterpolatedAndOutOfRange) {
  const Trajectory t = Line();
  common::Rigid3d pose;
  ASSERT_TRUE(LookUpPose(t, 1.0, 0.01, &pose));
  EXPECT_NEAR((pose.translation() - Eigen::Vector3d(2, 4, 0)).norm(), 0.0, 1e-12);
  ASSERT_TRUE(LookUpPose(t, 1.2, 0.3, &pose));
  EXPECT_NEAR((pose.translation() - Eigen::Vector3d(2.4, 4.8, 0)).norm(), 0.0, 1e-12);
  EXPECT_FALSE(LookUpPose(t, 1.2, 0.1, &pose));
  ASSERT_TRUE(LookUpPose(t, 2.04, 0.05, &pose));  // Past the end: nearest sample.
  EXPECT_NEAR((pose.translation() - Eigen::Vector3d(4, 8, 0)).norm(), 0.0, 1e-12);
  EXPECT_FALSE(LookUpPose(t, -0.2, 0.1, &pose));
  EXPECT_FALSE(LookUpPose(Trajectory(), 0.0, 1.0, &pose));
}

TEST(TrajectoryTest, AssociateByTimeKeepsOnlyCloseStamps) {
  const Trajectory gt = Line();
  Trajectory est = Line();
  est[1].stamp_s += 0.01;
  est[3].stamp_s += 0.1;
  const std::vector<PosePair> pairs = AssociateByTime(gt, est, 0.02);
  ASSERT_EQ(pairs.size(), 4u);
  EXPECT_DOUBLE_EQ(pairs[1].stamp_s, 0.51);
  EXPECT_DOUBLE_EQ(pairs[3].stamp_s, 2.0);
}

TEST(TrajectoryTest, AssociateByTimeIsOneToOne) {
  const Trajectory gt = Line();  // Stamps 0, 0.5, 1, 1.5, 2.
  Trajectory est;
  for (const double stamp : {0.49, 0.505, 0.51, 1.0}) {
    est.push_back(TimedPose3d{stamp, common::Rigid3d()});
  }
  const std::vector<PosePair> pairs = AssociateByTime(gt, est, 0.02);
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_DOUBLE_EQ(pairs[0].stamp_s, 0.505);  // Closest of the three claimants of gt 0.5.
  EXPECT_DOUBLE_EQ(pairs[0].gt.translation().x(), 1.0);
  EXPECT_DOUBLE_EQ(pairs[1].stamp_s, 1.0);
}

}  // namespace
}  // namespace eval
}  // namespace fusemap
