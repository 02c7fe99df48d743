#ifndef FUSEMAP_VISUAL_LOOP_BOW_VECTOR_H_
#define FUSEMAP_VISUAL_LOOP_BOW_VECTOR_H_

#include <cstdint>
#include <utility>
#include <vector>

namespace fusemap {
namespace visual_loop {

// A sparse bag-of-words vector: (word id, tf-idf weight) sorted by word id, without repeats,
// and L1-normalised (weights sum to 1) so that scores between images of different richness
// compare.
using BowVector = std::vector<std::pair<uint32_t, float>>;

// Sorts, merges repeated words (adding their weights) and L1-normalises.
void NormalizeBowVector(BowVector* vector);

// The L1 similarity of two normalised vectors, s = 1 - |v/|v| - w/|w||_1 / 2 in [0, 1]
// (Galvez-Lopez & Tardos 2012, eq. 2), evaluated over the shared words only:
// |a - b| = |a| + |b| - 2 min(a, b) for non-negative weights.
double L1Score(const BowVector& a, const BowVector& b);

// Dot product of two sorted vectors' shared words: the term each shared word adds to the score.
inline double L1SharedTerm(float a, float b) { return a < b ? a : b; }

}  // namespace visual_loop
}  // namespace fusemap

#endif  // FUSEMAP_VISUAL_LOOP_BOW_VECTOR_H_
