#ifndef FUSEMAP_VISUAL_LOOP_PATCH_ALIGNMENT_H_
#define FUSEMAP_VISUAL_LOOP_PATCH_ALIGNMENT_H_

#include <optional>
#include <string>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "fusemap/common/rigid_transform.h"
#include "fusemap/sensor/rgbd_frame.h"
#include "fusemap/visual_loop/geometric_verifier.h"
#include "fusemap/visual_loop/keyframe.h"

namespace fusemap {
namespace visual_loop {

// Where a keypoint lands in a second view, to a fraction of a pixel, by aligning its image
// patch there. Why: FAST puts a corner seen larger a little further out in the image than the
// same corner seen smaller, so a camera stepping towards what it sees measures its step long
// (in the simulator's corridor by 0.18 % a step, which adds up to a stretched map). The patch
// of the first view, warped through its local plane by the pose, finds the same physical point
// in the second view wherever FAST put the keypoint there.
struct PatchAlignmentOptions {
  int half_window_px = 7;         // the patch compared: (2 h + 1)^2 pixels of the first view
  int plane_half_window_px = 10;  // depth pixels the local plane is fitted to
  int max_iterations = 10;
  // A point is dropped when the alignment moves it further than this from the descriptor
  // match's keypoint in the second view (the same threshold PnP used to call it an inlier),
  // when its patch has too little texture to be placed, or when it does not converge.
  double max_shift_px = 3.0;
  double min_gradient = 4.0;  // grey levels per pixel, rms over the patch, in its weaker direction
  // RefineByPatchAlignment aligns at most max_points inliers, spread over all of them: a pose
  // needs no more, and each costs ~0.03 ms (real 640 x 480 images have 250-500 inliers); it
  // re-estimates the pose only when at least min_points of them align.
  int min_points = 20;
  int max_points = 300;
  bool IsValid(std::string* error) const;
};

// A camera image as the alignment reads it: grey CV_8UC1, depth registered to it (CV_32FC1
// metres, 0 or NaN for none; may be empty for the second view) and the intrinsics.
struct CameraImage {
  cv::Mat gray;
  cv::Mat depth_m;
  sensor::PinholeIntrinsics intrinsics;
};

// The pixel in b of the point seen at pixel_a in a (point_a: its 3D point in camera a), given
// the pose of camera a in camera b, starting from the warp of the pose; photometric gain and
// offset between the views are estimated with it. nullopt where the alignment fails (see
// PatchAlignmentOptions) or the point leaves either image.
std::optional<Eigen::Vector2d> AlignPatch(const CameraImage& a, const CameraImage& b,
                                          const common::Rigid3d& T_b_a,
                                          const Eigen::Vector2d& pixel_a,
                                          const Eigen::Vector3d& point_a,
                                          const Eigen::Vector2d& keypoint_b,
                                          const PatchAlignmentOptions& options);

// Refines a verified PnP result of keyframe b against keyframe a (VerifyKeyframes(a, b)) on the
// pixels: each inlier's point of a (at most max_points of them) is aligned into b (AlignPatch)
// and the pose re-estimated from those positions; the covariance and mean reprojection error
// follow. Returns how many inliers were aligned; the result is left as it was when fewer than
// options.min_points were.
int RefineByPatchAlignment(const Keyframe& a, const CameraImage& image_a, const Keyframe& b,
                           const CameraImage& image_b, const PatchAlignmentOptions& options,
                           VerificationResult* result);

}  // namespace visual_loop
}  // namespace fusemap

#endif  // FUSEMAP_VISUAL_LOOP_PATCH_ALIGNMENT_H_
