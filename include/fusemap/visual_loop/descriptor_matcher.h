#ifndef FUSEMAP_VISUAL_LOOP_DESCRIPTOR_MATCHER_H_
#define FUSEMAP_VISUAL_LOOP_DESCRIPTOR_MATCHER_H_

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace fusemap {
namespace visual_loop {

struct MatchingOptions {
  double ratio = 0.8;      // Lowe's ratio test on the two nearest Hamming distances
  int max_distance = 80;   // of 256 bits; beyond this two ORB descriptors are unrelated
  bool mutual = true;      // keep a -> b only if b's nearest in a is a as well
};

// Hamming matching of two CV_8UC1 N x 32 descriptor sets: queryIdx indexes a, trainIdx b.
// With groups for both (one id per descriptor, e.g. vocabulary nodes), only descriptors of the
// same group are compared (the nearest and second nearest, and the mutual check, within the
// group); otherwise brute force over all pairs.
std::vector<cv::DMatch> MatchDescriptors(const cv::Mat& a, const cv::Mat& b,
                                         const MatchingOptions& options,
                                         const std::vector<uint32_t>* groups_a = nullptr,
                                         const std::vector<uint32_t>* groups_b = nullptr);

}  // namespace visual_loop
}  // namespace fusemap

#endif  // FUSEMAP_VISUAL_LOOP_DESCRIPTOR_MATCHER_H_
