#include "fusemap/visual_loop/bow_vector.h"

#include <cmath>
#include <map>

#include <gtest/gtest.h>

#include "visual_loop/bow_test_util.h"

namespace fusemap {
namespace visual_loop {
namespace {

TEST(BowVectorTest, NormalizeSortsMergesAndSumsToOne) {
  BowVector bow = {{7, 1.0f}, {2, 2.0f}, {7, 1.0f}};
  NormalizeBowVector(&bow);
  ASSERT_EQ(bow.size(), 2u);
  EXPECT_EQ(bow[0].first, 2u);
  EXPECT_FLOAT_EQ(bow[0].second, 0.5f);
  EXPECT_EQ(bow[1].first, 7u);
  EXPECT_FLOAT_EQ(bow[1].second, 0.5f);
}

TEST(BowVectorTest, L1ScoreIsOneMinusHalfTheL1Distance) {
  std::mt19937 rng(1);
  for (int trial = 0; trial < 20; ++trial) {
    const BowVector a = testing::RandomPlace(&rng, 50);
    const BowVector b = testing::Revisit(a, 0.5, &rng);
    std::map<uint32_t, double> difference;
    for (const auto& [w, v] : a) difference[w] += v;
    for (const auto& [w, v] : b) difference[w] -= v;
    double l1 = 0.0;
    for (const auto& entry : difference) l1 += std::abs(entry.second);
    EXPECT_NEAR(L1Score(a, b), 1.0 - 0.5 * l1, 1e-5);
  }
  const BowVector a = testing::RandomPlace(&rng, 50);
  EXPECT_NEAR(L1Score(a, a), 1.0, 1e-5);
  EXPECT_EQ(L1Score(BowVector{{1, 1.0f}}, BowVector{{2, 1.0f}}), 0.0);
}

}  // namespace
}  // namespace visual_loop
}  // namespace fusemap
