#ifndef FUSEMAP_TEST_VISUAL_LOOP_BOW_TEST_UTIL_H_
#define FUSEMAP_TEST_VISUAL_LOOP_BOW_TEST_UTIL_H_

// Test-only random BoW vectors of "places": each place draws its words at random from a large
// vocabulary; a revisit keeps most of them and swaps some (new clutter, another viewpoint).

#include <random>

#include "fusemap/visual_loop/bow_vector.h"

namespace fusemap {
namespace visual_loop {
namespace testing {

constexpr int kTestWords = 10000;

inline BowVector RandomPlace(std::mt19937* rng, int words = 300) {
  BowVector bow;
  for (int i = 0; i < words; ++i) {
    bow.emplace_back(static_cast<uint32_t>((*rng)() % kTestWords), 1.0f + ((*rng)() % 100) / 100.0f);
  }
  NormalizeBowVector(&bow);
  return bow;
}

inline BowVector Revisit(const BowVector& place, double keep, std::mt19937* rng) {
  BowVector bow;
  for (const auto& entry : place) {
    if (((*rng)() % 1000) / 1000.0 < keep) {
      bow.push_back(entry);
    } else {
      bow.emplace_back(static_cast<uint32_t>((*rng)() % kTestWords), entry.second);
    }
  }
  NormalizeBowVector(&bow);
  return bow;
}

}  // namespace testing
}  // namespace visual_loop
}  // namespace fusemap

#endif  // FUSEMAP_TEST_VISUAL_LOOP_BOW_TEST_UTIL_H_
