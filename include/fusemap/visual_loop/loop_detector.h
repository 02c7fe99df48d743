#ifndef FUSEMAP_VISUAL_LOOP_LOOP_DETECTOR_H_
#define FUSEMAP_VISUAL_LOOP_LOOP_DETECTOR_H_

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "fusemap/visual_loop/geometric_verifier.h"
#include "fusemap/visual_loop/keyframe.h"
#include "fusemap/visual_loop/place_recognizer.h"
#include "fusemap/visual_loop/vocabulary.h"

namespace fusemap {
namespace visual_loop {

struct LoopDetectorOptions {
  PlaceRecognitionOptions recognition;
  VerificationOptions verification;
  // Islands verified per query, best first (verification is the expensive step).
  int max_verified_candidates = 3;
  bool IsValid(std::string* error) const;
};

// Defaults for a folder of images taken as one sequence (fusemap_vloop detect): images are far
// apart compared with a robot's keyframes, so only the 3 previous images are excluded and one
// earlier query must agree with the candidate island.
LoopDetectorOptions ImageSequenceDetectorOptions();

// A revisit: the query keyframe shows the place of an earlier one. verification.T_a_b is the
// pose of the query camera in the matched camera (a = match, b = query).
struct DetectedLoop {
  int query_id = -1;
  int match_id = -1;
  double score = 0.0;
  double normalized_score = 0.0;
  int consistent_queries = 0;
  VerificationResult verification;
};

// The appearance-only loop detector over a stream of keyframes: retrieval with temporal
// consistency, then geometric verification of the best islands. It owns the keyframes (what a
// session would checkpoint) and never looks at a pose estimate.
class LoopDetector {
 public:
  explicit LoopDetector(const LoopDetectorOptions& options, int num_words);

  // Queries with the keyframe, then stores it as a future candidate. Ids must increase and the
  // BoW vector be set. Returns the accepted loop, if any; candidates_out (optional) receives
  // every island considered, for diagnostics.
  std::optional<DetectedLoop> Process(Keyframe keyframe,
                                      std::vector<PlaceCandidate>* candidates_out = nullptr);

  // Drops a keyframe (its submap was trimmed).
  void Remove(int id);
  // Stores a keyframe as a candidate without querying with it (a restored checkpoint). Ids
  // must increase.
  void Restore(Keyframe keyframe);
  // Every keyframe held, by id.
  const std::map<int, Keyframe>& keyframes() const { return keyframes_; }
  const Keyframe* Find(int id) const;
  int size() const { return static_cast<int>(keyframes_.size()); }
  size_t BytesUsed() const;

 private:
  LoopDetectorOptions options_;
  PlaceRecognizer recognizer_;
  std::map<int, Keyframe> keyframes_;
  int last_id_ = -1;
};

}  // namespace visual_loop
}  // namespace fusemap

#endif  // FUSEMAP_VISUAL_LOOP_LOOP_DETECTOR_H_
