#include "fusemap/visual_loop/place_recognizer.h"

#include <algorithm>
#include <cassert>

namespace fusemap {
namespace visual_loop {

bool PlaceRecognitionOptions::IsValid(std::string* error) const {
  if (num_recent_excluded < 0 || max_results < 1 || island_gap < 0 || temporal_consistency < 0) {
    *error = "place recognition: counts must be non-negative (max_results positive)";
    return false;
  }
  if (!(min_normalized_score >= 0.0) || !(min_previous_score >= 0.0) || !(min_raw_score >= 0.0)) {
    *error = "place recognition: score thresholds must be non-negative";
    return false;
  }
  return true;
}

PlaceRecognizer::PlaceRecognizer(const PlaceRecognitionOptions& options, int num_words)
    : options_(options), database_(num_words) {
  std::string error;
  assert(options_.IsValid(&error));
}

void PlaceRecognizer::Add(int id, const BowVector& bow) { database_.Add(id, bow); }

std::vector<PlaceCandidate> PlaceRecognizer::Query(int query_id, const BowVector& bow,
                                                   const BowVector* previous_bow) {
  double scale = 0.0;  // 0: no normalisation, raw threshold
  if (previous_bow != nullptr) {
    scale = L1Score(bow, *previous_bow);
    if (scale < options_.min_previous_score) {
      previous_islands_.clear();
      return {};
    }
  }
  const int max_id = query_id - options_.num_recent_excluded;
  std::vector<DatabaseResult> results = database_.Query(bow, max_id, options_.max_results);
  std::vector<PlaceCandidate> matches;
  for (const DatabaseResult& result : results) {
    PlaceCandidate match;
    match.id = result.id;
    match.score = result.score;
    match.normalized_score = scale > 0.0 ? result.score / scale : result.score;
    const bool passes = scale > 0.0 ? match.normalized_score >= options_.min_normalized_score
                                    : match.score >= options_.min_raw_score;
    if (passes) matches.push_back(match);
  }
  std::sort(matches.begin(), matches.end(),
            [](const PlaceCandidate& a, const PlaceCandidate& b) { return a.id < b.id; });

  std::vector<PlaceCandidate> islands;
  for (const PlaceCandidate& match : matches) {
    if (islands.empty() || match.id - islands.back().island_last > options_.island_gap) {
      PlaceCandidate island = match;
      island.island_first = island.island_last = match.id;
      island.island_score = match.normalized_score;
      islands.push_back(island);
      continue;
    }
    PlaceCandidate& island = islands.back();
    island.island_last = match.id;
    island.island_score += match.normalized_score;
    if (match.normalized_score > island.normalized_score) {
      island.id = match.id;
      island.score = match.score;
      island.normalized_score = match.normalized_score;
    }
  }

  std::vector<Island> current;
  for (PlaceCandidate& island : islands) {
    int earlier = 0;
    for (const Island& previous : previous_islands_) {
      const bool overlap = island.island_first <= previous.last + options_.island_gap &&
                           previous.first <= island.island_last + options_.island_gap;
      if (overlap) earlier = std::max(earlier, previous.consistent_queries);
    }
    island.consistent_queries = earlier + 1;
    island.consistent = island.consistent_queries > options_.temporal_consistency;
    current.push_back({island.island_first, island.island_last, island.consistent_queries});
  }
  previous_islands_ = std::move(current);
  std::sort(islands.begin(), islands.end(), [](const PlaceCandidate& a, const PlaceCandidate& b) {
    return a.island_score != b.island_score ? a.island_score > b.island_score : a.id < b.id;
  });
  return islands;
}

}  // namespace visual_loop
}  // namespace fusemap
