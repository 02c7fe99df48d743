#include "fusemap/visual_loop/descriptor_matcher.h"

#include <opencv2/features2d.hpp>

namespace fusemap {
namespace visual_loop {

std::vector<cv::DMatch> MatchDescriptors(const cv::Mat& a, const cv::Mat& b,
                                         const MatchingOptions& options) {
  std::vector<cv::DMatch> matches;
  if (a.rows < 2 || b.rows < 2) return matches;
  cv::BFMatcher matcher(cv::NORM_HAMMING);
  std::vector<std::vector<cv::DMatch>> forward;
  matcher.knnMatch(a, b, forward, 2);
  std::vector<int> backward_best;
  if (options.mutual) {
    std::vector<cv::DMatch> backward;
    matcher.match(b, a, backward);
    backward_best.assign(b.rows, -1);
    for (const cv::DMatch& m : backward) backward_best[m.queryIdx] = m.trainIdx;
  }
  for (const auto& pair : forward) {
    if (pair.size() < 2) continue;
    const cv::DMatch& best = pair[0];
    if (best.distance > options.max_distance) continue;
    if (best.distance >= options.ratio * pair[1].distance) continue;
    if (options.mutual && backward_best[best.trainIdx] != best.queryIdx) continue;
    matches.push_back(best);
  }
  return matches;
}

}  // namespace visual_loop
}  // namespace fusemap
