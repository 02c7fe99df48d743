#include "fusemap/visual_loop/bow_vector.h"

#include <algorithm>

namespace fusemap {
namespace visual_loop {

void NormalizeBowVector(BowVector* vector) {
  std::sort(vector->begin(), vector->end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  BowVector merged;
  merged.reserve(vector->size());
  double sum = 0.0;
  for (const auto& [word, weight] : *vector) {
    if (!merged.empty() && merged.back().first == word) {
      merged.back().second += weight;
    } else {
      merged.emplace_back(word, weight);
    }
    sum += weight;
  }
  if (sum > 0.0) {
    for (auto& entry : merged) entry.second = static_cast<float>(entry.second / sum);
  }
  *vector = std::move(merged);
}

double L1Score(const BowVector& a, const BowVector& b) {
  double shared = 0.0;
  auto ia = a.begin();
  auto ib = b.begin();
  while (ia != a.end() && ib != b.end()) {
    if (ia->first < ib->first) {
      ++ia;
    } else if (ib->first < ia->first) {
      ++ib;
    } else {
      shared += L1SharedTerm(ia->second, ib->second);
      ++ia;
      ++ib;
    }
  }
  // With |a| = |b| = 1: 1 - (2 - 2 * shared) / 2 = shared.
  return shared;
}

}  // namespace visual_loop
}  // namespace fusemap
