#include "fusemap/visual_loop/vocabulary_trainer.h"

#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <set>

namespace fusemap {
namespace visual_loop {
namespace {

// Uniform in [0, 1) from the raw engine output: std::uniform_*_distribution is not specified
// bit for bit across standard libraries, mt19937 is.
double Uniform01(std::mt19937* rng) { return (*rng)() / 4294967296.0; }

// k-means++ seeding: the first centre uniformly, each next one with probability proportional to
// the squared distance to the nearest centre chosen so far.
std::vector<OrbDescriptor> SeedCentres(const std::vector<OrbDescriptor>& data,
                                       const std::vector<int>& members, int k,
                                       std::mt19937* rng) {
  std::vector<OrbDescriptor> centres;
  centres.push_back(data[members[(*rng)() % members.size()]]);
  std::vector<double> nearest_sq(members.size(), std::numeric_limits<double>::max());
  while (static_cast<int>(centres.size()) < k) {
    double total = 0.0;
    for (size_t i = 0; i < members.size(); ++i) {
      const double d = HammingDistance(data[members[i]].data(), centres.back().data());
      nearest_sq[i] = std::min(nearest_sq[i], d * d);
      total += nearest_sq[i];
    }
    if (total <= 0.0) break;  // fewer distinct descriptors than k
    double target = Uniform01(rng) * total;
    size_t pick = 0;
    for (; pick + 1 < members.size(); ++pick) {
      target -= nearest_sq[pick];
      if (target < 0.0) break;
    }
    centres.push_back(data[members[pick]]);
  }
  return centres;
}

OrbDescriptor MajorityOf(const std::vector<OrbDescriptor>& data, const std::vector<int>& members) {
  std::array<int, 256> ones{};
  for (int m : members) {
    for (int byte = 0; byte < 32; ++byte) {
      const uint8_t value = data[m][byte];
      for (int bit = 0; bit < 8; ++bit) ones[byte * 8 + bit] += (value >> bit) & 1;
    }
  }
  OrbDescriptor centre{};
  for (int b = 0; b < 256; ++b) {
    // Ties go to 1, as in DBoW2's FORB::meanValue: 2 * ones >= n.
    if (2 * ones[b] >= static_cast<int>(members.size())) centre[b / 8] |= (1 << (b % 8));
  }
  return centre;
}

// k-majority on `members`: returns the clusters (each a list of indices into data) and their
// centres; clusters never come back empty.
void KMajority(const std::vector<OrbDescriptor>& data, const std::vector<int>& members, int k,
               int max_iterations, std::mt19937* rng, std::vector<OrbDescriptor>* centres,
               std::vector<std::vector<int>>* clusters) {
  *centres = SeedCentres(data, members, k, rng);
  std::vector<int> assignment(members.size(), -1);
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    bool changed = false;
    for (size_t i = 0; i < members.size(); ++i) {
      int best = 0;
      int best_distance = std::numeric_limits<int>::max();
      for (int c = 0; c < static_cast<int>(centres->size()); ++c) {
        const int d = HammingDistance(data[members[i]].data(), (*centres)[c].data());
        if (d < best_distance) {
          best_distance = d;
          best = c;
        }
      }
      if (assignment[i] != best) {
        assignment[i] = best;
        changed = true;
      }
    }
    clusters->assign(centres->size(), {});
    for (size_t i = 0; i < members.size(); ++i) (*clusters)[assignment[i]].push_back(members[i]);
    if (!changed) break;
    for (size_t c = 0; c < centres->size(); ++c) {
      if (!(*clusters)[c].empty()) (*centres)[c] = MajorityOf(data, (*clusters)[c]);
    }
  }
  // A centre that lost all its members is dropped rather than kept as an unreachable word.
  for (size_t c = clusters->size(); c-- > 0;) {
    if ((*clusters)[c].empty()) {
      clusters->erase(clusters->begin() + c);
      centres->erase(centres->begin() + c);
    }
  }
}

}  // namespace

bool VocabularyTrainingOptions::IsValid(std::string* error) const {
  if (branching < 2 || levels < 1 || max_iterations < 1) {
    *error = "branching must be at least 2, levels and max_iterations at least 1";
    return false;
  }
  if (std::pow(static_cast<double>(branching), levels) > 1e7) {
    *error = "branching^levels above 10 million words";
    return false;
  }
  return true;
}

Vocabulary TrainVocabulary(const std::vector<cv::Mat>& descriptors_per_image,
                           const VocabularyTrainingOptions& options) {
  std::string error;
  assert(options.IsValid(&error));
  std::vector<OrbDescriptor> data;
  std::vector<int> image_of;
  for (size_t image = 0; image < descriptors_per_image.size(); ++image) {
    const cv::Mat& d = descriptors_per_image[image];
    assert(d.empty() || (d.type() == CV_8UC1 && d.cols == 32));
    for (int r = 0; r < d.rows; ++r) {
      OrbDescriptor descriptor;
      std::memcpy(descriptor.data(), d.ptr<uint8_t>(r), 32);
      data.push_back(descriptor);
      image_of.push_back(static_cast<int>(image));
    }
  }
  assert(!data.empty());

  std::mt19937 rng(options.seed);
  std::vector<Vocabulary::Node> nodes(1);
  std::vector<OrbDescriptor> centres(1, OrbDescriptor{});
  // Breadth first, so children of a node are contiguous and come after it.
  struct Pending {
    int node;
    int level;
    std::vector<int> members;
  };
  std::vector<Pending> queue;
  std::vector<int> all(data.size());
  for (size_t i = 0; i < data.size(); ++i) all[i] = static_cast<int>(i);
  queue.push_back({0, 0, std::move(all)});
  std::vector<std::vector<int>> word_members;
  for (size_t head = 0; head < queue.size(); ++head) {
    Pending pending = std::move(queue[head]);
    const bool leaf = pending.level == options.levels || pending.members.size() <= 1;
    if (leaf) {
      nodes[pending.node].word = static_cast<int32_t>(word_members.size());
      word_members.push_back(std::move(pending.members));
      continue;
    }
    std::vector<OrbDescriptor> cluster_centres;
    std::vector<std::vector<int>> clusters;
    KMajority(data, pending.members, options.branching, options.max_iterations, &rng,
              &cluster_centres, &clusters);
    nodes[pending.node].first_child = static_cast<uint32_t>(nodes.size());
    nodes[pending.node].num_children = static_cast<uint32_t>(clusters.size());
    for (size_t c = 0; c < clusters.size(); ++c) {
      const int child = static_cast<int>(nodes.size());
      nodes.emplace_back();
      centres.push_back(cluster_centres[c]);
      // A single cluster cannot split further: stop here rather than loop on it.
      const int next_level = clusters.size() == 1 ? options.levels : pending.level + 1;
      queue.push_back({child, next_level, std::move(clusters[c])});
    }
  }

  const double num_images = static_cast<double>(descriptors_per_image.size());
  std::vector<float> weights(word_members.size());
  for (size_t w = 0; w < word_members.size(); ++w) {
    std::set<int> images;
    for (int m : word_members[w]) images.insert(image_of[m]);
    weights[w] = static_cast<float>(std::log(num_images / static_cast<double>(images.size())));
  }
  return Vocabulary(options.branching, options.levels, std::move(nodes), std::move(centres),
                    std::move(weights));
}

}  // namespace visual_loop
}  // namespace fusemap
