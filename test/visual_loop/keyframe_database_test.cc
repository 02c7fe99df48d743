#include "fusemap/visual_loop/keyframe_database.h"

#include <gtest/gtest.h>

#include "visual_loop/bow_test_util.h"

namespace fusemap {
namespace visual_loop {
namespace {

TEST(KeyframeDatabaseTest, TheTruePlaceRanksFirstAmongAThousand) {
  std::mt19937 rng(2);
  KeyframeDatabase database(testing::kTestWords);
  std::vector<BowVector> places;
  for (int id = 0; id < 1000; ++id) {
    places.push_back(testing::RandomPlace(&rng));
    database.Add(id, places.back());
  }
  EXPECT_EQ(database.size(), 1000);
  for (int id : {0, 37, 500, 999}) {
    const BowVector query = testing::Revisit(places[id], 0.6, &rng);
    const std::vector<DatabaseResult> results = database.Query(query, 1000, 5);
    ASSERT_FALSE(results.empty());
    EXPECT_EQ(results[0].id, id);
    EXPECT_NEAR(results[0].score, L1Score(query, places[id]), 1e-4);
    EXPECT_GT(results[0].score, 2.0 * results[1].score);
  }
}

TEST(KeyframeDatabaseTest, RecentAndRemovedKeyframesAreNotReturned) {
  std::mt19937 rng(3);
  KeyframeDatabase database(testing::kTestWords);
  std::vector<BowVector> places;
  for (int id = 0; id < 50; ++id) {
    places.push_back(testing::RandomPlace(&rng));
    database.Add(id, places.back());
  }
  // The query is keyframe 40 itself: below max_id 40 it cannot be found.
  for (const DatabaseResult& r : database.Query(places[40], 40, 50)) EXPECT_LT(r.id, 40);
  EXPECT_EQ(database.Query(places[12], 50, 1)[0].id, 12);
  database.Remove(12, places[12]);
  EXPECT_EQ(database.size(), 49);
  for (const DatabaseResult& r : database.Query(places[12], 50, 50)) EXPECT_NE(r.id, 12);
}

}  // namespace
}  // namespace visual_loop
}  // namespace fusemap
