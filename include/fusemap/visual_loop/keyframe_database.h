#ifndef FUSEMAP_VISUAL_LOOP_KEYFRAME_DATABASE_H_
#define FUSEMAP_VISUAL_LOOP_KEYFRAME_DATABASE_H_

#include <cstdint>
#include <vector>

#include "fusemap/visual_loop/bow_vector.h"

namespace fusemap {
namespace visual_loop {

struct DatabaseResult {
  int id = -1;
  double score = 0.0;  // L1 score in [0, 1]
};

// An inverted index from words to the keyframes that contain them (Galvez-Lopez & Tardos 2012,
// Sec. IV): a query only touches the keyframes sharing a word with it, so its cost grows with
// the posting lists of its words, not with the size of the map. Keyframe ids are non-negative
// and unique; removing one (a trimmed submap) drops it from every list.
class KeyframeDatabase {
 public:
  explicit KeyframeDatabase(int num_words) : postings_(num_words) {}

  void Add(int id, const BowVector& bow);
  void Remove(int id, const BowVector& bow);
  int size() const { return size_; }

  // The best max_results keyframes with id < max_id (so recent ones can be left out), by L1
  // score, best first. Keyframes sharing no word with the query are never returned.
  std::vector<DatabaseResult> Query(const BowVector& bow, int max_id, int max_results) const;

 private:
  struct Posting {
    int id;
    float weight;
  };
  std::vector<std::vector<Posting>> postings_;
  int size_ = 0;
  int max_id_seen_ = -1;
  // Scratch accumulators indexed by id, reused across queries (only touched entries are reset).
  mutable std::vector<float> scores_;
  mutable std::vector<int> touched_;
};

}  // namespace visual_loop
}  // namespace fusemap

#endif  // FUSEMAP_VISUAL_LOOP_KEYFRAME_DATABASE_H_
