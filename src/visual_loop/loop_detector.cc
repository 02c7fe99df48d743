#include "fusemap/visual_loop/loop_detector.h"

#include <cassert>

namespace fusemap {
namespace visual_loop {

bool LoopDetectorOptions::IsValid(std::string* error) const {
  if (max_verified_candidates < 1) {
    *error = "loop detector: max_verified_candidates must be positive";
    return false;
  }
  return recognition.IsValid(error) && verification.IsValid(error);
}

LoopDetectorOptions ImageSequenceDetectorOptions() {
  LoopDetectorOptions options;
  options.recognition.num_recent_excluded = 3;
  options.recognition.temporal_consistency = 1;
  return options;
}

LoopDetector::LoopDetector(const LoopDetectorOptions& options, int num_words)
    : options_(options), recognizer_(options.recognition, num_words) {
  std::string error;
  assert(options_.IsValid(&error));
}

std::optional<DetectedLoop> LoopDetector::Process(Keyframe keyframe,
                                                  std::vector<PlaceCandidate>* candidates_out) {
  assert(keyframe.id > last_id_);
  const Keyframe* previous = Find(last_id_);
  std::vector<PlaceCandidate> candidates =
      recognizer_.Query(keyframe.id, keyframe.bow, previous != nullptr ? &previous->bow : nullptr);
  std::optional<DetectedLoop> loop;
  int verified = 0;
  for (const PlaceCandidate& candidate : candidates) {
    if (!candidate.consistent || verified == options_.max_verified_candidates) continue;
    const Keyframe* match = Find(candidate.id);
    if (match == nullptr) continue;
    ++verified;
    VerificationResult result = VerifyKeyframes(*match, keyframe, options_.verification);
    if (!result.verified) continue;
    loop = DetectedLoop{keyframe.id, candidate.id, candidate.score, candidate.normalized_score,
                        candidate.consistent_queries, std::move(result)};
    break;
  }
  if (candidates_out != nullptr) *candidates_out = std::move(candidates);
  last_id_ = keyframe.id;
  recognizer_.Add(keyframe.id, keyframe.bow);
  keyframes_.emplace(keyframe.id, std::move(keyframe));
  return loop;
}

void LoopDetector::Remove(int id) {
  const auto it = keyframes_.find(id);
  if (it == keyframes_.end()) return;
  recognizer_.Remove(id, it->second.bow);
  keyframes_.erase(it);
}

void LoopDetector::Restore(Keyframe keyframe) {
  assert(keyframe.id > last_id_);
  last_id_ = keyframe.id;
  recognizer_.Add(keyframe.id, keyframe.bow);
  keyframes_.emplace(keyframe.id, std::move(keyframe));
}

const Keyframe* LoopDetector::Find(int id) const {
  const auto it = keyframes_.find(id);
  return it == keyframes_.end() ? nullptr : &it->second;
}

size_t LoopDetector::BytesUsed() const {
  size_t bytes = 0;
  for (const auto& entry : keyframes_) bytes += entry.second.BytesUsed();
  return bytes;
}

}  // namespace visual_loop
}  // namespace fusemap
