#ifndef FUSEMAP_VISUAL_LOOP_VISUAL_LOOP_CHECKER_H_
#define FUSEMAP_VISUAL_LOOP_VISUAL_LOOP_CHECKER_H_

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "fusemap/common/rigid_transform.h"
#include "fusemap/sensor/rgbd_frame.h"
#include "fusemap/visual_loop/keyframe_selector.h"
#include "fusemap/visual_loop/loop_arbiter.h"
#include "fusemap/visual_loop/loop_detector.h"
#include "fusemap/visual_loop/patch_alignment.h"
#include "fusemap/visual_loop/planar_constraint.h"

namespace fusemap {
namespace visual_loop {

struct VisualLoopCheckerOptions {
  KeyframeSelectorOptions selector;
  OrbOptions orb;
  KeyframeOptions keyframe;
  LoopDetectorOptions detector;
  PlanarConstraintOptions planar;
  // A laser loop is positively contradicted only when both keyframes are rich (this many
  // keypoints with depth in the stored one), the laser says their views overlap (bases this
  // close and this little turned), and yet geometry finds at most max_contradiction_inliers
  // consistent matches (chance level for unrelated views).
  int min_points_to_contradict = 300;
  double max_overlap_distance_m = 1.0;
  double max_overlap_yaw_rad = 0.5;
  int max_contradiction_inliers = 12;
  // The images of the two latest keyframes are held, and a match between them (the camera's
  // motion from one keyframe to the next) is refined on their pixels (RefineByPatchAlignment,
  // when at least patch_alignment.min_points of its inliers align). Older keyframes keep no pixels.
  bool refine_latest_on_pixels = true;
  PatchAlignmentOptions patch_alignment;
  bool IsValid(std::string* error) const;
};

// One camera image as the checker takes it: grey or BGR, depth registered to it (CV_32FC1
// metres, empty for none) and the camera's mount on the robot base.
struct CameraFrame {
  double stamp_s = 0.0;
  cv::Mat image;
  cv::Mat depth_m;
  sensor::PinholeIntrinsics intrinsics;
  common::Rigid3d T_base_camera;
};

// A verified visual loop as a planar constraint between the robot bases of two keyframes.
struct VisualLoopConstraint {
  int query_keyframe = -1;
  int match_keyframe = -1;
  int query_node = -1;
  int match_node = -1;
  int match_submap = -1;
  common::Rigid2d T_match_base_query_base;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
  int inliers = 0;
  double score = 0.0;
};

struct VisualCheckResult {
  VisualCheck check = VisualCheck::kNotChecked;
  std::optional<VisualLoopConstraint> constraint;  // when kVerified
  std::string reason;
  // Between the two latest keyframes (refine_latest_on_pixels): the inliers aligned on pixels,
  // and whether the pose was re-estimated from them.
  int aligned_points = 0;
  bool refined_on_pixels = false;
};

// A keyframe as a checkpoint keeps it: what the detector holds and the camera mount.
struct SavedKeyframe {
  Keyframe keyframe;
  common::Rigid3d T_base_camera;
};

struct VisualLoopCheckerStats {
  int keyframes = 0;        // held now
  int candidates = 0;       // queries with a consistent island
  int verified = 0;         // visual loops returned
  int rejected = 0;         // candidates refused by geometry or by the floor-plane check
};

// The ORB visual loop checker as the pose graph side sees it: it keeps keyframes (by motion or
// time, tagged with their node and submap), finds revisits by appearance alone and returns them
// as planar base-to-base constraints, and checks a laser loop's place on request. The caller
// turns constraints into node-in-submap measurements (ToSubmapMeasurement) and arbitrates
// (ArbitrateLoop). No threads: the session runs it on its own back-end thread.
class VisualLoopChecker {
 public:
  VisualLoopChecker(const VisualLoopCheckerOptions& options,
                    std::shared_ptr<const Vocabulary> vocabulary);

  struct FrameResult {
    bool keyframe = false;  // the frame was kept
    int keyframe_id = -1;   // its id, when kept
    std::optional<VisualLoopConstraint> loop;
    std::string rejection;  // why a candidate was refused, if one was
  };
  // Offers a frame with the robot's local-SLAM pose and the node/submap it belongs to.
  FrameResult AddFrame(const CameraFrame& frame, const common::Rigid2d& T_local_tracking, int node,
                       int submap);

  // Verifies keyframe query against keyframe match where a laser loop says the query base
  // stands at expected_T_match_base_query_base. A pair is verified once (the most recent
  // pairs are remembered): only the judgement of a failed verification depends on the place.
  VisualCheckResult CheckPlace(int query_keyframe, int match_keyframe,
                               const common::Rigid2d& expected_T_match_base_query_base);

  // How many of the descriptor matches between two stored keyframes the relative pose of their
  // bases explains (CountMatchesExplained, through each keyframe's camera mount); -1 if either
  // keyframe is gone.
  int MatchesExplained(int match_keyframe, int query_keyframe,
                       const common::Rigid2d& T_match_base_query_base) const;

  // Keyframes of a submap, and the keyframe whose node is nearest to `node` (-1 if none).
  std::vector<int> KeyframesOfSubmap(int submap) const;
  int KeyframeNearestNode(int node) const;
  // Releases the keyframes of a trimmed submap.
  void RemoveSubmap(int submap);

  VisualLoopCheckerStats stats() const;
  const LoopDetector& detector() const { return detector_; }

  // Checkpoints: the keyframes held, by increasing id, and the next id to give out.
  std::vector<SavedKeyframe> ExportKeyframes() const;
  int next_keyframe_id() const { return next_id_; }
  // Only on a checker without keyframes: takes them back (ids increasing, below next_id) as
  // loop candidates; counters restart.
  void RestoreKeyframes(std::vector<SavedKeyframe> keyframes, int next_id);

 private:
  std::optional<VisualLoopConstraint> ToConstraint(const Keyframe& match, const Keyframe& query,
                                                   const VerificationResult& result,
                                                   std::string* rejection) const;

  // What verifying one keyframe against another measured, whatever place a laser loop gives:
  // the laser loops of consecutive nodes ask for the same pair (simulated ring with rooms: 1,558
  // checks of 805 pairs), and verification is most of the checker's cost.
  struct PlaceVerification {
    VisualCheckResult result;  // kVerified, or kNotChecked and why it failed
    int inliers = 0;           // what a contradiction is judged on
  };
  const PlaceVerification& VerifyPlace(const Keyframe& query, const Keyframe& match);

  VisualLoopCheckerOptions options_;
  std::shared_ptr<const Vocabulary> vocabulary_;
  OrbExtractor extractor_;
  KeyframeSelector selector_;
  LoopDetector detector_;
  std::map<int, common::Rigid3d> T_base_camera_;  // per keyframe id
  std::map<int, CameraImage> latest_images_;      // of the two latest keyframes
  // By (query, match) keyframe id; the pairs of the newest queries are kept.
  std::map<std::pair<int, int>, PlaceVerification> place_verifications_;
  int next_id_ = 0;
  VisualLoopCheckerStats stats_;
};

// The node-in-submap measurement implied by a visual constraint, given where the matched
// keyframe's base stands in the submap (from the pose graph); covariance rotated into the
// submap frame (first order, the matched pose taken as exact).
LoopMeasurement2D ToSubmapMeasurement(const common::Rigid2d& T_submap_match_base,
                                      const VisualLoopConstraint& constraint);

}  // namespace visual_loop
}  // namespace fusemap

#endif  // FUSEMAP_VISUAL_LOOP_VISUAL_LOOP_CHECKER_H_
