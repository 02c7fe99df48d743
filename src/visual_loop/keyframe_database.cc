#include "fusemap/visual_loop/keyframe_database.h"

#include <algorithm>
#include <cassert>

namespace fusemap {
namespace visual_loop {

void KeyframeDatabase::Add(int id, const BowVector& bow) {
  assert(id >= 0);
  for (const auto& [word, weight] : bow) {
    assert(word < postings_.size());
    postings_[word].push_back({id, weight});
  }
  max_id_seen_ = std::max(max_id_seen_, id);
  ++size_;
}

void KeyframeDatabase::Remove(int id, const BowVector& bow) {
  for (const auto& entry : bow) {
    auto& list = postings_[entry.first];
    list.erase(std::remove_if(list.begin(), list.end(), [id](const Posting& p) { return p.id == id; }),
               list.end());
  }
  --size_;
}

std::vector<DatabaseResult> KeyframeDatabase::Query(const BowVector& bow, int max_id,
                                                    int max_results) const {
  if (static_cast<int>(scores_.size()) <= max_id_seen_) scores_.assign(max_id_seen_ + 1, 0.0f);
  touched_.clear();
  for (const auto& [word, query_weight] : bow) {
    for (const Posting& posting : postings_[word]) {
      if (posting.id >= max_id) continue;
      float& score = scores_[posting.id];
      if (score == 0.0f) touched_.push_back(posting.id);
      // L1 score of normalised vectors: the sum over shared words of min(q, v) (bow_vector.h).
      score += L1SharedTerm(query_weight, posting.weight);
    }
  }
  std::vector<DatabaseResult> results;
  results.reserve(touched_.size());
  for (int id : touched_) {
    results.push_back({id, scores_[id]});
    scores_[id] = 0.0f;
  }
  const auto better = [](const DatabaseResult& a, const DatabaseResult& b) {
    return a.score != b.score ? a.score > b.score : a.id < b.id;
  };
  if (static_cast<int>(results.size()) > max_results) {
    std::partial_sort(results.begin(), results.begin() + max_results, results.end(), better);
    results.resize(max_results);
  } else {
    std::sort(results.begin(), results.end(), better);
  }
  return results;
}

}  // namespace visual_loop
}  // namespace fusemap
