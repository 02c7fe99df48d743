#include "fusemap/pose_graph/moved_submaps.h"

#include <gtest/gtest.h>

#include "fusemap/common/math.h"

namespace fusemap {
namespace pose_graph {
namespace {

using common::Rigid2d;

TEST(MovedSubmapsTest, ListsExactlyThoseOverThreshold) {
  const std::vector<Rigid2d> before = {Rigid2d(0, 0, 0), Rigid2d(1, 0, 0.1), Rigid2d(2, 0, 0.2),
                                       Rigid2d(3, 0, 0.3), Rigid2d(4, 0, common::kPi - 1e-8)};
  std::vector<Rigid2d> after = before;
  after[1] = Rigid2d(1, 2e-6, 0.1);             // moved 2e-6 m > 1e-6 m
  after[2] = Rigid2d(2 + 5e-7, 0, 0.2 + 5e-8);  // under both thresholds
  after[3] = Rigid2d(3, 0, 0.3 + 2e-7);         // turned 2e-7 rad > 1e-7 rad
  after[4] = Rigid2d(4, 0, -common::kPi + 1e-8);  // 2e-8 rad across the +-pi seam
  after.push_back(Rigid2d(9, 9, 0));             // new, not moved
  const std::vector<SubmapMove> moves = MovedSubmaps(before, after);
  ASSERT_EQ(moves.size(), 2u);
  EXPECT_EQ(moves[0].submap, 1);
  EXPECT_EQ(moves[0].T_map_submap_old.y(), 0.0);
  EXPECT_EQ(moves[0].T_map_submap_new.y(), 2e-6);
  EXPECT_EQ(moves[1].submap, 3);

  EXPECT_TRUE(MovedSubmaps(before, before).empty());
}

TEST(MovedSubmapsTest, OneThresholdForTranslationAndAngle) {
  EXPECT_FALSE(SubmapMoved(Rigid2d(0, 0, 0), Rigid2d(0.9 * kSubmapMoveThresholdM, 0, 0)));
  EXPECT_TRUE(SubmapMoved(Rigid2d(0, 0, 0), Rigid2d(1.1 * kSubmapMoveThresholdM, 0, 0)));
  EXPECT_FALSE(SubmapMoved(Rigid2d(0, 0, 0), Rigid2d(0, 0, 0.9 * kSubmapMoveThresholdRad)));
  EXPECT_TRUE(SubmapMoved(Rigid2d(0, 0, 0), Rigid2d(0, 0, 1.1 * kSubmapMoveThresholdRad)));
}

}  // namespace
}  // namespace pose_graph
}  // namespace fusemap
