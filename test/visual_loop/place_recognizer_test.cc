#include "fusemap/visual_loop/place_recognizer.h"

#include <gtest/gtest.h>

#include "visual_loop/bow_test_util.h"

namespace fusemap {
namespace visual_loop {
namespace {

// A route of 60 distinct places with some overlap between neighbours, as keyframes see it.
std::vector<BowVector> Route(std::mt19937* rng) {
  std::vector<BowVector> route;
  route.push_back(testing::RandomPlace(rng));
  for (int i = 1; i < 60; ++i) route.push_back(testing::Revisit(route.back(), 0.3, rng));
  return route;
}

PlaceRecognitionOptions Options() {
  PlaceRecognitionOptions options;
  options.num_recent_excluded = 10;
  options.temporal_consistency = 2;
  return options;
}

TEST(PlaceRecognizerTest, ASingleLuckyHitIsNotConsistent) {
  std::mt19937 rng(4);
  const std::vector<BowVector> route = Route(&rng);
  PlaceRecognizer recognizer(Options(), testing::kTestWords);
  for (int id = 0; id < 60; ++id) {
    const auto islands = recognizer.Query(id, route[id], id > 0 ? &route[id - 1] : nullptr);
    for (const auto& island : islands) EXPECT_FALSE(island.consistent) << id;
    recognizer.Add(id, route[id]);
  }
  // New ground, then one frame that happens to look like place 20, then new ground again.
  BowVector previous = route[59];
  int id = 60;
  for (int i = 0; i < 3; ++i, ++id) {
    const BowVector fresh = testing::Revisit(previous, 0.3, &rng);
    recognizer.Query(id, fresh, &previous);
    previous = fresh;
  }
  const BowVector lucky = testing::Revisit(route[20], 0.5, &rng);
  const auto islands = recognizer.Query(id++, lucky, &previous);
  ASSERT_FALSE(islands.empty());
  EXPECT_NEAR(islands[0].id, 20, 1);
  EXPECT_FALSE(islands[0].consistent);
  const BowVector after = testing::Revisit(previous, 0.3, &rng);
  for (const auto& island : recognizer.Query(id++, after, &lucky)) EXPECT_FALSE(island.consistent);
}

TEST(PlaceRecognizerTest, ARevisitSeenByConsecutiveQueriesBecomesConsistent) {
  std::mt19937 rng(5);
  const std::vector<BowVector> route = Route(&rng);
  PlaceRecognizer recognizer(Options(), testing::kTestWords);
  for (int id = 0; id < 60; ++id) {
    recognizer.Query(id, route[id], id > 0 ? &route[id - 1] : nullptr);
    recognizer.Add(id, route[id]);
  }
  // The robot drives along places 10, 11, 12, 13 again.
  const BowVector* previous = &route[59];
  std::vector<BowVector> queries;
  for (int k = 0; k < 4; ++k) queries.push_back(testing::Revisit(route[10 + k], 0.6, &rng));
  for (int k = 0; k < 4; ++k) {
    const auto islands = recognizer.Query(60 + k, queries[k], previous);
    previous = &queries[k];
    ASSERT_FALSE(islands.empty()) << k;
    EXPECT_LE(islands[0].island_first, 10 + k);
    EXPECT_GE(islands[0].island_last, 10 + k);
    EXPECT_EQ(islands[0].consistent_queries, k + 1);
    EXPECT_EQ(islands[0].consistent, k >= 2) << k;
  }
}

}  // namespace
}  // namespace visual_loop
}  // namespace fusemap
