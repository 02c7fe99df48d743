#include "fusemap/visual_loop/visual_loop_checker.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdlib>
#include <iterator>
#include <utility>

namespace fusemap {
namespace visual_loop {
namespace {

// Verified keyframe pairs remembered: a laser loop's checks ask at most a few views of its
// submap for one query keyframe, and loops arrive in the order the robot passes their places,
// so a few hundred pairs cover every query still being asked about (a few hundred bytes each).
constexpr size_t kMaxPlaceVerifications = 512;

}  // namespace

bool VisualLoopCheckerOptions::IsValid(std::string* error) const {
  if (!selector.IsValid(error) || !orb.IsValid(error) || !detector.IsValid(error) ||
      !planar.IsValid(error) || !patch_alignment.IsValid(error)) {
    return false;
  }
  if (min_points_to_contradict < 1 || !(max_overlap_distance_m > 0.0) ||
      !(max_overlap_yaw_rad > 0.0) || max_contradiction_inliers < 0) {
    *error = "visual loop checker: contradiction thresholds must be positive";
    return false;
  }
  return true;
}

VisualLoopChecker::VisualLoopChecker(const VisualLoopCheckerOptions& options,
                                     std::shared_ptr<const Vocabulary> vocabulary)
    : options_(options),
      vocabulary_(std::move(vocabulary)),
      extractor_(options.orb),
      selector_(options.selector),
      detector_(options.detector, vocabulary_->num_words()) {
  std::string error;
  assert(options_.IsValid(&error));
}

VisualLoopChecker::FrameResult VisualLoopChecker::AddFrame(const CameraFrame& frame,
                                                           const common::Rigid2d& T_local_tracking,
                                                           int node, int submap) {
  FrameResult out;
  if (!selector_.Select(frame.stamp_s, T_local_tracking)) return out;
  out.keyframe = true;
  Keyframe keyframe = MakeKeyframe(frame.image, frame.depth_m, frame.intrinsics, extractor_,
                                   vocabulary_.get(), options_.keyframe);
  keyframe.id = next_id_++;
  out.keyframe_id = keyframe.id;
  keyframe.node = node;
  keyframe.submap = submap;
  keyframe.stamp_s = frame.stamp_s;
  T_base_camera_[keyframe.id] = frame.T_base_camera;
  if (options_.refine_latest_on_pixels) {
    CameraImage& image = latest_images_[keyframe.id];
    image.gray = ToGray(frame.image).clone();  // held after the caller's frame is gone
    image.depth_m = frame.depth_m.clone();
    image.intrinsics = frame.intrinsics;
    while (latest_images_.size() > 2) latest_images_.erase(latest_images_.begin());
  }
  std::vector<PlaceCandidate> candidates;
  const std::optional<DetectedLoop> loop = detector_.Process(std::move(keyframe), &candidates);
  stats_.candidates += std::any_of(candidates.begin(), candidates.end(),
                                   [](const PlaceCandidate& c) { return c.consistent; });
  if (!loop) return out;
  const Keyframe* match = detector_.Find(loop->match_id);
  const Keyframe* query = detector_.Find(loop->query_id);
  out.loop = ToConstraint(*match, *query, loop->verification, &out.rejection);
  if (out.loop) {
    out.loop->score = loop->normalized_score;
    ++stats_.verified;
  } else {
    ++stats_.rejected;
  }
  return out;
}

std::optional<VisualLoopConstraint> VisualLoopChecker::ToConstraint(const Keyframe& match,
                                                                    const Keyframe& query,
                                                                    const VerificationResult& result,
                                                                    std::string* rejection) const {
  if (!result.verified || !result.metric) {
    *rejection = result.verified ? "no depth: the relative pose has no scale" : result.reason;
    return std::nullopt;
  }
  const PlanarConstraint planar =
      ToPlanarConstraint(result.T_a_b, result.covariance, T_base_camera_.at(match.id),
                         T_base_camera_.at(query.id), options_.planar);
  if (!planar.accepted) {
    *rejection = planar.reason;
    return std::nullopt;
  }
  VisualLoopConstraint constraint;
  constraint.query_keyframe = query.id;
  constraint.match_keyframe = match.id;
  constraint.query_node = query.node;
  constraint.match_node = match.node;
  constraint.match_submap = match.submap;
  constraint.T_match_base_query_base = planar.T_base_a_base_b;
  constraint.covariance = planar.covariance;
  constraint.inliers = result.inliers;
  return constraint;
}

const VisualLoopChecker::PlaceVerification& VisualLoopChecker::VerifyPlace(const Keyframe& query,
                                                                           const Keyframe& match) {
  const std::pair<int, int> key(query.id, match.id);
  const auto known = place_verifications_.find(key);
  if (known != place_verifications_.end()) return known->second;
  PlaceVerification place;
  VisualCheckResult& out = place.result;
  VerificationResult result = VerifyKeyframes(match, query, options_.detector.verification);
  const auto image_match = latest_images_.find(match.id);
  const auto image_query = latest_images_.find(query.id);
  if (image_match != latest_images_.end() && image_query != latest_images_.end()) {
    out.aligned_points = RefineByPatchAlignment(
        match, image_match->second, query, image_query->second, options_.patch_alignment, &result);
    out.refined_on_pixels =
        result.verified && out.aligned_points >= options_.patch_alignment.min_points;
  }
  out.constraint = ToConstraint(match, query, result, &out.reason);
  if (out.constraint) out.check = VisualCheck::kVerified;
  place.inliers = result.inliers;
  // Laser loops ask about the places the robot passes now: the oldest queries go first.
  while (place_verifications_.size() >= kMaxPlaceVerifications) {
    place_verifications_.erase(place_verifications_.begin());
  }
  return place_verifications_.emplace(key, std::move(place)).first->second;
}

VisualCheckResult VisualLoopChecker::CheckPlace(int query_keyframe, int match_keyframe,
                                                const common::Rigid2d& expected) {
  VisualCheckResult out;
  const Keyframe* query = detector_.Find(query_keyframe);
  const Keyframe* match = detector_.Find(match_keyframe);
  if (query == nullptr || match == nullptr) {
    out.reason = "no such keyframe";
    return out;
  }
  const PlaceVerification& place = VerifyPlace(*query, *match);
  out = place.result;
  if (out.check == VisualCheck::kVerified) return out;
  // Not verified: a contradiction only if the camera had every chance to confirm the place.
  const bool rich = match->num_points_with_depth() >= options_.min_points_to_contradict &&
                    static_cast<int>(query->keypoints.size()) >= options_.min_points_to_contradict;
  const bool should_overlap = expected.translation().norm() <= options_.max_overlap_distance_m &&
                              std::abs(expected.angle_rad()) <= options_.max_overlap_yaw_rad;
  if (rich && should_overlap && place.inliers <= options_.max_contradiction_inliers) {
    out.check = VisualCheck::kContradicted;
    out.reason = "rich views that should overlap share only " + std::to_string(place.inliers) +
                 " consistent matches";
  }
  return out;
}

int VisualLoopChecker::MatchesExplained(int match_keyframe, int query_keyframe,
                                        const common::Rigid2d& T_match_base_query_base) const {
  const Keyframe* query = detector_.Find(query_keyframe);
  const Keyframe* match = detector_.Find(match_keyframe);
  if (query == nullptr || match == nullptr) return -1;
  const common::Rigid3d T_match_camera_query_camera =
      T_base_camera_.at(match_keyframe).inverse() *
      common::Rigid3d::FromRigid2d(T_match_base_query_base) * T_base_camera_.at(query_keyframe);
  return CountMatchesExplained(*match, *query, T_match_camera_query_camera,
                               options_.detector.verification);
}

std::vector<int> VisualLoopChecker::KeyframesOfSubmap(int submap) const {
  std::vector<int> ids;
  for (const auto& entry : T_base_camera_) {
    const Keyframe* k = detector_.Find(entry.first);
    if (k != nullptr && k->submap == submap) ids.push_back(k->id);
  }
  return ids;
}

int VisualLoopChecker::KeyframeNearestNode(int node) const {
  int best = -1;
  int best_gap = 0;
  for (const auto& entry : T_base_camera_) {
    const Keyframe* k = detector_.Find(entry.first);
    if (k == nullptr || k->node < 0) continue;
    const int gap = std::abs(k->node - node);
    if (best < 0 || gap < best_gap) {
      best = k->id;
      best_gap = gap;
    }
  }
  return best;
}

void VisualLoopChecker::RemoveSubmap(int submap) {
  for (int id : KeyframesOfSubmap(submap)) {
    detector_.Remove(id);
    T_base_camera_.erase(id);
    latest_images_.erase(id);
  }
  for (auto it = place_verifications_.begin(); it != place_verifications_.end();) {
    const bool gone =
        detector_.Find(it->first.first) == nullptr || detector_.Find(it->first.second) == nullptr;
    it = gone ? place_verifications_.erase(it) : std::next(it);
  }
}

std::vector<SavedKeyframe> VisualLoopChecker::ExportKeyframes() const {
  std::vector<SavedKeyframe> saved;
  for (const auto& [id, keyframe] : detector_.keyframes()) {
    saved.push_back({keyframe, T_base_camera_.at(id)});
  }
  return saved;
}

void VisualLoopChecker::RestoreKeyframes(std::vector<SavedKeyframe> keyframes, int next_id) {
  assert(detector_.size() == 0);
  for (SavedKeyframe& saved : keyframes) {
    assert(saved.keyframe.id < next_id);
    T_base_camera_[saved.keyframe.id] = saved.T_base_camera;
    detector_.Restore(std::move(saved.keyframe));
  }
  next_id_ = next_id;
}

VisualLoopCheckerStats VisualLoopChecker::stats() const {
  VisualLoopCheckerStats stats = stats_;
  stats.keyframes = detector_.size();
  return stats;
}

LoopMeasurement2D ToSubmapMeasurement(const common::Rigid2d& T_submap_match_base,
                                      const VisualLoopConstraint& constraint) {
  LoopMeasurement2D measurement;
  measurement.T_submap_node = T_submap_match_base * constraint.T_match_base_query_base;
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  A.topLeftCorner<2, 2>() = T_submap_match_base.rotation().toRotationMatrix();
  measurement.covariance = A * constraint.covariance * A.transpose();
  measurement.visual_inliers = constraint.inliers;
  return measurement;
}

}  // namespace visual_loop
}  // namespace fusemap
