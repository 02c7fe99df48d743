#ifndef FUSEMAP_TEST_VISUAL_LOOP_VOCABULARY_TEST_UTIL_H_
#define FUSEMAP_TEST_VISUAL_LOOP_VOCABULARY_TEST_UTIL_H_

// Test-only synthetic binary descriptors: cluster centres and noisy copies (a few bits flipped),
// a stand-in for ORB descriptors of repeated structures.

#include <random>
#include <vector>

#include <opencv2/core.hpp>

#include "fusemap/visual_loop/vocabulary.h"

namespace fusemap {
namespace visual_loop {
namespace testing {

inline OrbDescriptor RandomDescriptor(std::mt19937* rng) {
  OrbDescriptor d;
  for (auto& byte : d) byte = static_cast<uint8_t>((*rng)() & 0xff);
  return d;
}

inline OrbDescriptor FlipBits(OrbDescriptor d, int bits, std::mt19937* rng) {
  for (int i = 0; i < bits; ++i) {
    const int bit = static_cast<int>((*rng)() % 256);
    d[bit / 8] ^= static_cast<uint8_t>(1 << (bit % 8));
  }
  return d;
}

inline cv::Mat ToMat(const std::vector<OrbDescriptor>& descriptors) {
  cv::Mat mat(static_cast<int>(descriptors.size()), 32, CV_8UC1);
  for (size_t i = 0; i < descriptors.size(); ++i) {
    std::copy(descriptors[i].begin(), descriptors[i].end(), mat.ptr<uint8_t>(static_cast<int>(i)));
  }
  return mat;
}

}  // namespace testing
}  // namespace visual_loop
}  // namespace fusemap

#endif  // FUSEMAP_TEST_VISUAL_LOOP_VOCABULARY_TEST_UTIL_H_
