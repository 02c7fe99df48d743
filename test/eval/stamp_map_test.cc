#include "fusemap/eval/stamp_map.h"

#include <gtest/gtest.h>

#include <vector>

namespace fusemap {
namespace eval {
namespace {

TEST(StampMapTest, ARecordPrintedAloneIsFoundAnywhereInItsRoundingInterval) {
  const StampMap map({{10.0, 10.0, 0.01}, {10.5, 10.5, 0.01}});
  StampMap::Match match;
  EXPECT_DOUBLE_EQ(map.ToOutputTime(10.0043, &match), 10.0);
  EXPECT_EQ(match, StampMap::Match::kExact);
  EXPECT_DOUBLE_EQ(map.ToOutputTime(10.4951, &match), 10.5);
  EXPECT_EQ(match, StampMap::Match::kExact);
}

TEST(StampMapTest, InstantsSpreadOverTheIntervalMapOntoThemselves) {
  // Three instants printing 1401.34 (the importer spread them at 1/6, 3/6 and 5/6 of the
  // interval); the second has two records (an ODOM and a scan with it).
  const double step = 0.01 / 3.0;
  const double u0 = 1401.335 + 0.5 * step, u1 = u0 + step, u2 = u1 + step;
  const StampMap map({{1401.33, 1401.33, 0.01},
                      {u0, 1401.34, 0.01},
                      {u1, 1401.34, 0.01},
                      {u1, 1401.34, 0.01},
                      {u2, 1401.34, 0.01},
                      {1401.35, 1401.35, 0.01}});
  for (const double t : {u0, u1, 0.5 * (u1 + u2), u2}) {
    EXPECT_NEAR(map.ToOutputTime(t), t, 1e-9) << t;
  }
  // Beyond the outer instants (still inside the interval) the outer instant is kept.
  EXPECT_DOUBLE_EQ(map.ToOutputTime(1401.3351), u0);
  EXPECT_DOUBLE_EQ(map.ToOutputTime(1401.3449), u2);
}

TEST(StampMapTest, ALateStampFollowsItsRecord) {
  // Printed 6.0 between 5.0 and 5.6 in file order; the importer placed it at 5.3.
  const StampMap map({{5.0, 5.0, 0.01}, {5.3, 6.0, 0.01}, {5.6, 5.6, 0.01}, {6.4, 6.4, 0.01}});
  StampMap::Match match;
  EXPECT_DOUBLE_EQ(map.ToOutputTime(6.002, &match), 5.3);
  EXPECT_EQ(match, StampMap::Match::kExact);
}

TEST(StampMapTest, MovedInstantsOfOneRunAreNotInterpolatedBetween) {
  // Two instants printing 5.00 that the importer moved 0.5 s apart: a time is given one of
  // them, never a time between them where no record was.
  const StampMap map({{3.0, 5.0, 0.01}, {3.5, 5.0, 0.01}});
  EXPECT_DOUBLE_EQ(map.ToOutputTime(4.9960), 3.0);
  EXPECT_DOUBLE_EQ(map.ToOutputTime(5.0040), 3.5);
}

TEST(StampMapTest, AStampPrintedInTwoPlacesTakesTheNearerAndSaysSo) {
  const StampMap map({{6.4, 7.0, 0.01}, {6.5, 6.5, 0.01}, {7.0, 7.0, 0.01}});
  StampMap::Match match;
  EXPECT_DOUBLE_EQ(map.ToOutputTime(7.001, &match), 7.0);
  EXPECT_EQ(match, StampMap::Match::kAmbiguous);
}

TEST(StampMapTest, AnUnprintedTimeIsReturnedUnchanged) {
  const StampMap map({{1.0, 1.0, 0.01}, {2.0, 2.0, 0.01}});
  StampMap::Match match;
  EXPECT_DOUBLE_EQ(map.ToOutputTime(1.5, &match), 1.5);
  EXPECT_EQ(match, StampMap::Match::kUnmatched);
  const StampMap empty({});
  EXPECT_DOUBLE_EQ(empty.ToOutputTime(3.0, &match), 3.0);
  EXPECT_EQ(match, StampMap::Match::kUnmatched);
}

TEST(StampMapTest, MapRelationTimesMovesBothStampsAndCounts) {
  const StampMap map({{5.0, 5.0, 0.01}, {5.3, 6.0, 0.01}, {5.6, 5.6, 0.01}});
  std::vector<Relation> relations = {{5.001, 6.002, common::Rigid2d()},
                                     {5.6, 9.0, common::Rigid2d()}};
  const StampMapCounts counts = MapRelationTimes(map, &relations);
  EXPECT_DOUBLE_EQ(relations[0].t1_s, 5.0);
  EXPECT_DOUBLE_EQ(relations[0].t2_s, 5.3);
  EXPECT_DOUBLE_EQ(relations[1].t1_s, 5.6);
  EXPECT_DOUBLE_EQ(relations[1].t2_s, 9.0);
  EXPECT_EQ(counts.exact, 3);
  EXPECT_EQ(counts.ambiguous, 0);
  EXPECT_EQ(counts.unmatched, 1);
}

}  // namespace
}  // namespace eval
}  // namespace fusemap
