#include "fusemap/ground_truth/tag_pose.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgproc.hpp>

namespace fusemap {
namespace ground_truth {
namespace {

// AprilTag 3 reports pixel coordinates with pixel centres at integer + 0.5 (it fits quad edges
// to pixel squares); calibrated intrinsics put them at integers. Subtracted before any pose math.
constexpr double kDetectorPixelOffset = 0.5;

cv::Matx33d CameraMatrix(const sensor::PinholeIntrinsics& intrinsics) {
  return cv::Matx33d(intrinsics.fx, 0, intrinsics.cx, 0, intrinsics.fy, intrinsics.cy, 0, 0, 1);
}

double QuadArea(const TagDetection& d) {
  double twice_area = 0.0;
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d& a = d.corners_px[k];
    const Eigen::Vector2d& b = d.corners_px[(k + 1) % 4];
    twice_area += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * std::abs(twice_area);
}

common::Rigid3d FromRvecTvec(const cv::Mat& rvec, const cv::Mat& tvec) {
  cv::Mat R_cv;
  cv::Rodrigues(rvec, R_cv);
  Eigen::Matrix3d R;
  cv::cv2eigen(R_cv, R);
  return common::Rigid3d(
      Eigen::Vector3d(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2)),
      Eigen::Quaterniond(R));
}

}  // namespace

std::array<Eigen::Vector3d, 4> TagCornersInTagFrame(double size_m) {
  const double h = 0.5 * size_m;
  return {Eigen::Vector3d(-h, -h, 0), Eigen::Vector3d(h, -h, 0), Eigen::Vector3d(h, h, 0),
          Eigen::Vector3d(-h, h, 0)};
}

bool EstimateTagPose(const TagDetection& detection, const sensor::PinholeIntrinsics& intrinsics,
                     double size_m, common::Rigid3d* T_camera_tag) {
  assert(size_m > 0.0 && intrinsics.fx > 0.0 && intrinsics.fy > 0.0);
  // IPPE_SQUARE wants the corners in the order (-,+), (+,+), (+,-), (-,-): ours reversed.
  const auto corners = TagCornersInTagFrame(size_m);
  std::vector<cv::Point3d> object_points;
  std::vector<cv::Point2d> image_points;
  for (int k = 3; k >= 0; --k) {
    object_points.emplace_back(corners[k].x(), corners[k].y(), corners[k].z());
    image_points.emplace_back(detection.corners_px[k].x() - kDetectorPixelOffset,
                              detection.corners_px[k].y() - kDetectorPixelOffset);
  }
  cv::Mat rvec, tvec;
  if (!cv::solvePnP(object_points, image_points, cv::Mat(CameraMatrix(intrinsics)), cv::noArray(),
                    rvec, tvec, false, cv::SOLVEPNP_IPPE_SQUARE)) {
    return false;
  }
  const common::Rigid3d pose = FromRvecTvec(rvec, tvec);
  if (!pose.translation().allFinite() || pose.translation().z() <= 0.0) return false;
  *T_camera_tag = pose;
  return true;
}

bool EstimateCameraPose(const std::vector<TagDetection>& detections, const TagMap& tag_map,
                        const sensor::PinholeIntrinsics& intrinsics, CameraPoseEstimate* estimate) {
  *estimate = CameraPoseEstimate();
  std::vector<cv::Point3d> object_points;
  std::vector<cv::Point2d> image_points;
  const TagDetection* seed = nullptr;
  for (const TagDetection& d : detections) {
    const auto it = tag_map.find(d.id);
    if (it == tag_map.end()) {
      estimate->unknown_ids.push_back(d.id);
      continue;
    }
    estimate->used_ids.push_back(d.id);
    const auto corners = TagCornersInTagFrame(it->second.size_m);
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d p_map = it->second.T_map_tag * corners[k];
      object_points.emplace_back(p_map.x(), p_map.y(), p_map.z());
      image_points.emplace_back(d.corners_px[k].x() - kDetectorPixelOffset,
                                d.corners_px[k].y() - kDetectorPixelOffset);
    }
    if (seed == nullptr || QuadArea(d) > QuadArea(*seed)) seed = &d;
  }
  if (seed == nullptr) return false;
  const SurveyedTag& seed_tag = tag_map.at(seed->id);
  common::Rigid3d T_camera_tag;
  if (!EstimateTagPose(*seed, intrinsics, seed_tag.size_m, &T_camera_tag)) return false;
  const common::Rigid3d T_camera_map = T_camera_tag * seed_tag.T_map_tag.inverse();

  cv::Mat R_cv;
  cv::eigen2cv(Eigen::Matrix3d(T_camera_map.rotation().toRotationMatrix()), R_cv);
  cv::Mat rvec, tvec;
  cv::Rodrigues(R_cv, rvec);
  tvec = (cv::Mat_<double>(3, 1) << T_camera_map.translation().x(), T_camera_map.translation().y(),
          T_camera_map.translation().z());
  const cv::Mat K(CameraMatrix(intrinsics));
  if (!cv::solvePnP(object_points, image_points, K, cv::noArray(), rvec, tvec, true,
                    cv::SOLVEPNP_ITERATIVE)) {
    return false;
  }
  std::vector<cv::Point2d> reprojected;
  cv::projectPoints(object_points, rvec, tvec, K, cv::noArray(), reprojected);
  double sum_sq = 0.0;
  for (size_t i = 0; i < reprojected.size(); ++i) {
    const cv::Point2d e = reprojected[i] - image_points[i];
    sum_sq += e.dot(e);
  }
  estimate->rms_reprojection_px = std::sqrt(sum_sq / reprojected.size());
  estimate->T_map_camera = FromRvecTvec(rvec, tvec).inverse();
  return true;
}

Eigen::Vector2d ProjectToPixel(const common::Rigid3d& T_map_camera,
                               const sensor::PinholeIntrinsics& intrinsics,
                               const Eigen::Vector3d& p_map) {
  const Eigen::Vector3d p = T_map_camera.inverse() * p_map;
  return Eigen::Vector2d(intrinsics.fx * p.x() / p.z() + intrinsics.cx + kDetectorPixelOffset,
                         intrinsics.fy * p.y() / p.z() + intrinsics.cy + kDetectorPixelOffset);
}

}  // namespace ground_truth
}  // namespace fusemap
