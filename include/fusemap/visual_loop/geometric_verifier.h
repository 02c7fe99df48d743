#ifndef FUSEMAP_VISUAL_LOOP_GEOMETRIC_VERIFIER_H_
#define FUSEMAP_VISUAL_LOOP_GEOMETRIC_VERIFIER_H_

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "fusemap/common/rigid_transform.h"
#include "fusemap/visual_loop/descriptor_matcher.h"
#include "fusemap/visual_loop/keyframe.h"
#include "fusemap/visual_loop/pose_covariance.h"

namespace fusemap {
namespace visual_loop {

struct VerificationOptions {
  MatchingOptions matching;
  int min_inliers = 30;
  // RANSAC on PnP (pixels) and on the epipolar geometry (pixels, Sampson distance).
  double pnp_threshold_px = 3.0;
  double epipolar_threshold_px = 1.0;
  int ransac_iterations = 500;
  double ransac_confidence = 0.999;
  // After refinement, the inliers' mean reprojection error must stay below this.
  double max_mean_reprojection_px = 1.5;
  // Inliers must spread over the image: at least min_occupied_cells of a grid_cols x grid_rows
  // grid, in both images; a loop seen through one poster corner is not a loop.
  int grid_cols = 4;
  int grid_rows = 4;
  int min_occupied_cells = 4;
  bool IsValid(std::string* error) const;
};

enum class VerificationMethod { kPnp, kEssential, kFundamental };
const char* ToString(VerificationMethod method);

struct VerificationResult {
  bool verified = false;
  std::string reason;  // why not verified (empty when verified)
  VerificationMethod method = VerificationMethod::kPnp;
  int matches = 0;
  int inliers = 0;
  double mean_reprojection_px = 0.0;  // PnP: reprojection; epipolar: Sampson distance
  int occupied_cells = 0;
  // The pose of camera b in camera a. With PnP metric; from the essential matrix the translation
  // is a unit vector (scale unknown); from the fundamental matrix there is no pose.
  bool has_pose = false;
  bool metric = false;
  common::Rigid3d T_a_b;
  Matrix6d covariance = Matrix6d::Identity();  // of T_a_b, see PnpCovariance(); PnP only
  std::vector<cv::DMatch> inlier_matches;      // queryIdx in a, trainIdx in b
};

// Does keyframe b show the place of keyframe a? With depth in a: PnP + RANSAC on a's 3D points
// and b's keypoints, then Levenberg-Marquardt on the inliers; without: the essential matrix
// when both have intrinsics, else the fundamental matrix.
VerificationResult VerifyKeyframes(const Keyframe& a, const Keyframe& b,
                                   const VerificationOptions& options);

// How many of the descriptor matches VerifyKeyframes finds between a and b a given pose of
// camera b in camera a explains: those with depth in a that it projects within
// options.pnp_threshold_px of their keypoint in b. 0 without depth in a or intrinsics in b.
// A verified pose that another pose explains about as well is not evidence against that one.
int CountMatchesExplained(const Keyframe& a, const Keyframe& b, const common::Rigid3d& T_a_b,
                          const VerificationOptions& options);

// OpenCV's camera matrix of the intrinsics, and a pose in solvePnP's terms (rotation vector,
// translation; CV_64F 3 x 1) and back: what the PnP steps here and in RefineByPatchAlignment share.
cv::Matx33d CameraMatrix(const sensor::PinholeIntrinsics& intrinsics);
common::Rigid3d FromRvecTvec(const cv::Mat& rvec, const cv::Mat& tvec);
void ToRvecTvec(const common::Rigid3d& pose, cv::Mat* rvec, cv::Mat* tvec);

}  // namespace visual_loop
}  // namespace fusemap

#endif  // FUSEMAP_VISUAL_LOOP_GEOMETRIC_VERIFIER_H_
