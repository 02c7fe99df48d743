#ifndef FUSEMAP_VISUAL_LOOP_PLACE_RECOGNIZER_H_
#define FUSEMAP_VISUAL_LOOP_PLACE_RECOGNIZER_H_

#include <string>
#include <vector>

#include "fusemap/visual_loop/bow_vector.h"
#include "fusemap/visual_loop/keyframe_database.h"

namespace fusemap {
namespace visual_loop {

struct PlaceRecognitionOptions {
  // The keyframes just before the query see the same place trivially: not loop candidates.
  int num_recent_excluded = 20;
  int max_results = 50;
  // Scores are divided by the query's score against its previous keyframe (Galvez-Lopez &
  // Tardos 2012, eq. 3), so one threshold suits rich and poor scenes; a query that barely
  // resembles its own predecessor (a blur, a turn) gives no usable scale and is skipped.
  double min_normalized_score = 0.3;
  double min_previous_score = 0.005;
  // Without a previous keyframe (the first query) the raw score must pass this.
  double min_raw_score = 0.05;
  // Matches whose ids lie at most island_gap apart form one island (one place seen in a row);
  // the island's score is the sum of its members', its representative the best member.
  int island_gap = 3;
  // Temporal consistency: an island must overlap (within island_gap) an island of each of the
  // previous temporal_consistency queries before it is reported consistent.
  int temporal_consistency = 2;
  bool IsValid(std::string* error) const;
};

struct PlaceCandidate {
  int id = -1;                  // the island's best keyframe
  double score = 0.0;           // its raw L1 score
  double normalized_score = 0.0;
  int island_first = -1;
  int island_last = -1;
  double island_score = 0.0;    // sum of normalised scores in the island
  int consistent_queries = 0;   // this query plus the earlier consecutive ones that agreed
  bool consistent = false;      // consistent_queries > temporal_consistency
};

// Bag-of-words place recognition over a keyframe database: retrieval, normalisation, islands
// and temporal consistency (Galvez-Lopez & Tardos 2012, Sec. V). It looks at appearance only:
// no pose estimate enters, so it can find a place the laser's drifted pose no longer expects.
class PlaceRecognizer {
 public:
  PlaceRecognizer(const PlaceRecognitionOptions& options, int num_words);

  // Adds a keyframe as a future loop candidate. Ids must increase.
  void Add(int id, const BowVector& bow);
  void Remove(int id, const BowVector& bow) { database_.Remove(id, bow); }
  int size() const { return database_.size(); }

  // Islands for keyframe query_id (already added or not), best island first. previous_bow is
  // the query's previous keyframe (null for the first). Updates the temporal-consistency state,
  // so call once per keyframe, in order.
  std::vector<PlaceCandidate> Query(int query_id, const BowVector& bow,
                                    const BowVector* previous_bow);

  const KeyframeDatabase& database() const { return database_; }

 private:
  struct Island {
    int first;
    int last;
    int consistent_queries;
  };
  PlaceRecognitionOptions options_;
  KeyframeDatabase database_;
  std::vector<Island> previous_islands_;
};

}  // namespace visual_loop
}  // namespace fusemap

#endif  // FUSEMAP_VISUAL_LOOP_PLACE_RECOGNIZER_H_
