#include "fusemap/visual_loop/descriptor_matcher.h"

#include <limits>
#include <unordered_map>

#include <opencv2/features2d.hpp>

#include "fusemap/visual_loop/vocabulary.h"

namespace fusemap {
namespace visual_loop {
namespace {

struct Nearest {
  int best = -1;
  int best_distance = std::numeric_limits<int>::max();
  int second_distance = std::numeric_limits<int>::max();
  void Offer(int index, int distance) {
    if (distance < best_distance) {
      second_distance = best_distance;
      best_distance = distance;
      best = index;
    } else if (distance < second_distance) {
      second_distance = distance;
    }
  }
};

bool Passes(const Nearest& n, const MatchingOptions& options) {
  return n.best >= 0 && n.best_distance <= options.max_distance &&
         n.best_distance < options.ratio * n.second_distance;
}

std::vector<cv::DMatch> MatchInGroups(const cv::Mat& a, const cv::Mat& b, const MatchingOptions& options,
                                      const std::vector<uint32_t>& groups_a,
                                      const std::vector<uint32_t>& groups_b) {
  std::unordered_map<uint32_t, std::vector<int>> members_b;
  for (int j = 0; j < b.rows; ++j) members_b[groups_b[j]].push_back(j);
  std::vector<Nearest> forward(a.rows);
  std::vector<Nearest> backward(b.rows);
  for (int i = 0; i < a.rows; ++i) {
    const auto it = members_b.find(groups_a[i]);
    if (it == members_b.end()) continue;
    const uint8_t* da = a.ptr<uint8_t>(i);
    for (int j : it->second) {
      const int d = HammingDistance(da, b.ptr<uint8_t>(j));
      forward[i].Offer(j, d);
      backward[j].Offer(i, d);
    }
  }
  std::vector<cv::DMatch> matches;
  for (int i = 0; i < a.rows; ++i) {
    if (!Passes(forward[i], options)) continue;
    const int j = forward[i].best;
    if (options.mutual && backward[j].best != i) continue;
    matches.emplace_back(i, j, static_cast<float>(forward[i].best_distance));
  }
  return matches;
}

}  // namespace

std::vector<cv::DMatch> MatchDescriptors(const cv::Mat& a, const cv::Mat& b,
                                         const MatchingOptions& options,
                                         const std::vector<uint32_t>* groups_a,
                                         const std::vector<uint32_t>* groups_b) {
  std::vector<cv::DMatch> matches;
  if (a.rows < 2 || b.rows < 2) return matches;
  if (groups_a != nullptr && groups_b != nullptr && static_cast<int>(groups_a->size()) == a.rows &&
      static_cast<int>(groups_b->size()) == b.rows) {
    return MatchInGroups(a, b, options, *groups_a, *groups_b);
  }
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
