#ifndef FUSEMAP_GROUND_TRUTH_TAG_POSE_H_
#define FUSEMAP_GROUND_TRUTH_TAG_POSE_H_

#include <Eigen/Core>
#include <array>
#include <vector>

#include "fusemap/common/rigid_transform.h"
#include "fusemap/ground_truth/tag_detector.h"
#include "fusemap/ground_truth/tag_map.h"
#include "fusemap/sensor/rgbd_frame.h"

namespace fusemap {
namespace ground_truth {

// The four corners in the tag frame of tag_map.h, in TagDetection::corners_px order:
// (s/2) * (-1,-1), (1,-1), (1,1), (-1,1).
std::array<Eigen::Vector3d, 4> TagCornersInTagFrame(double size_m);

// Pose of one tag in the camera optical frame from its corners by IPPE (Collins & Bartoli 2014,
// "Infinitesimal Plane-Based Pose Estimation"; cv::SOLVEPNP_IPPE_SQUARE), which picks the
// lower-reprojection-error one of the two planar solutions. Debian's AprilTag 3 does not export
// the matd_* functions its own estimate_tag_pose needs from callers, hence OpenCV.
// Returns false for a degenerate detection.
bool EstimateTagPose(const TagDetection& detection, const sensor::PinholeIntrinsics& intrinsics,
                     double size_m, common::Rigid3d* T_camera_tag);

// A camera pose in the map from every known tag of one image.
struct CameraPoseEstimate {
  common::Rigid3d T_map_camera;
  std::vector<int> used_ids;     // Tags in the map that contributed their corners.
  std::vector<int> unknown_ids;  // Detected, but not in the map: reported, not used.
  double rms_reprojection_px = 0.0;
};

// Solves one camera pose from all known tags' corners jointly: the single-tag pose of the
// largest tag in the image seeds a Levenberg-Marquardt refinement of the reprojection error
// over all corners at their map positions (cv::solvePnP, SOLVEPNP_ITERATIVE with guess).
// Returns false (unknown_ids still filled) when no detected tag is in the map.
bool EstimateCameraPose(const std::vector<TagDetection>& detections, const TagMap& tag_map,
                        const sensor::PinholeIntrinsics& intrinsics, CameraPoseEstimate* estimate);

// Projects map points with T_map_camera and pinhole intrinsics (pixel centres at +0.5, as the
// detector reports). For tests and reprojection checks.
Eigen::Vector2d ProjectToPixel(const common::Rigid3d& T_map_camera,
                               const sensor::PinholeIntrinsics& intrinsics,
                               const Eigen::Vector3d& p_map);

}  // namespace ground_truth
}  // namespace fusemap

#endif  // FUSEMAP_GROUND_TRUTH_TAG_POSE_H_
