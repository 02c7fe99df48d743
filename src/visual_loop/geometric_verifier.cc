#include "fusemap/visual_loop/geometric_verifier.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

namespace fusemap {
namespace visual_loop {
namespace {

bool HasIntrinsics(const Keyframe& k) { return k.intrinsics.fx > 0.0 && k.intrinsics.fy > 0.0; }

int OccupiedCells(const std::vector<cv::Point2f>& points, int width, int height,
                  const VerificationOptions& options) {
  std::vector<bool> occupied(options.grid_cols * options.grid_rows, false);
  for (const cv::Point2f& p : points) {
    const int cx = std::clamp(static_cast<int>(p.x * options.grid_cols / width), 0, options.grid_cols - 1);
    const int cy = std::clamp(static_cast<int>(p.y * options.grid_rows / height), 0, options.grid_rows - 1);
    occupied[cy * options.grid_cols + cx] = true;
  }
  return static_cast<int>(std::count(occupied.begin(), occupied.end(), true));
}

// Inlier count and spread (in both images) against the options; sets the reason on failure.
bool CheckSupport(const Keyframe& a, const Keyframe& b, const VerificationOptions& options,
                  VerificationResult* result) {
  result->inliers = static_cast<int>(result->inlier_matches.size());
  if (result->inliers < options.min_inliers) {
    result->reason = "inliers " + std::to_string(result->inliers) + " < " + std::to_string(options.min_inliers);
    return false;
  }
  std::vector<cv::Point2f> in_a;
  std::vector<cv::Point2f> in_b;
  for (const cv::DMatch& m : result->inlier_matches) {
    in_a.push_back(a.keypoints[m.queryIdx]);
    in_b.push_back(b.keypoints[m.trainIdx]);
  }
  result->occupied_cells = std::min(OccupiedCells(in_a, a.image_width, a.image_height, options),
                                    OccupiedCells(in_b, b.image_width, b.image_height, options));
  if (result->occupied_cells < options.min_occupied_cells) {
    result->reason = "inliers cover " + std::to_string(result->occupied_cells) + " grid cells < " +
                     std::to_string(options.min_occupied_cells);
    return false;
  }
  return true;
}

void VerifyPnp(const Keyframe& a, const Keyframe& b, const std::vector<cv::DMatch>& matches,
               const VerificationOptions& options, VerificationResult* result) {
  result->method = VerificationMethod::kPnp;
  std::vector<cv::Point3f> object;
  std::vector<cv::Point2f> image;
  std::vector<cv::DMatch> used;
  for (const cv::DMatch& m : matches) {
    const Eigen::Vector3f& p = a.points_camera[m.queryIdx];
    if (!std::isfinite(p.z())) continue;
    object.emplace_back(p.x(), p.y(), p.z());
    image.push_back(b.keypoints[m.trainIdx]);
    used.push_back(m);
  }
  if (static_cast<int>(used.size()) < options.min_inliers) {
    result->reason = "matches with depth " + std::to_string(used.size()) + " < " +
                     std::to_string(options.min_inliers);
    return;
  }
  const cv::Matx33d K = CameraMatrix(b.intrinsics);
  cv::Mat rvec;
  cv::Mat tvec;
  std::vector<int> inliers;
  if (!cv::solvePnPRansac(object, image, K, cv::noArray(), rvec, tvec, false,
                          options.ransac_iterations, static_cast<float>(options.pnp_threshold_px),
                          options.ransac_confidence, inliers, cv::SOLVEPNP_EPNP) ||
      static_cast<int>(inliers.size()) < 6) {
    result->reason = "PnP RANSAC found no pose";
    return;
  }
  // Refine on the inliers, re-select inliers with the refined pose, refine once more.
  for (int round = 0; round < 2; ++round) {
    std::vector<cv::Point3f> in_object;
    std::vector<cv::Point2f> in_image;
    for (int i : inliers) {
      in_object.push_back(object[i]);
      in_image.push_back(image[i]);
    }
    cv::solvePnPRefineLM(in_object, in_image, K, cv::noArray(), rvec, tvec);
    std::vector<cv::Point2f> projected;
    cv::projectPoints(object, rvec, tvec, K, cv::noArray(), projected);
    inliers.clear();
    for (size_t i = 0; i < object.size(); ++i) {
      if (cv::norm(projected[i] - image[i]) <= options.pnp_threshold_px) inliers.push_back(static_cast<int>(i));
    }
    if (inliers.size() < 6) break;
  }
  for (int i : inliers) result->inlier_matches.push_back(used[i]);
  if (!CheckSupport(a, b, options, result)) return;

  const common::Rigid3d T_b_a = FromRvecTvec(rvec, tvec);
  result->T_a_b = T_b_a.inverse();
  std::vector<Eigen::Vector3d> points_a;
  std::vector<Eigen::Vector2d> pixels_b;
  for (int i : inliers) {
    points_a.emplace_back(object[i].x, object[i].y, object[i].z);
    pixels_b.emplace_back(image[i].x, image[i].y);
  }
  result->mean_reprojection_px = MeanReprojectionPx(T_b_a, points_a, pixels_b, b.intrinsics);
  result->has_pose = true;
  result->metric = true;
  if (result->mean_reprojection_px > options.max_mean_reprojection_px) {
    result->reason = "mean reprojection error " + std::to_string(result->mean_reprojection_px) + " px";
    return;
  }
  result->covariance = PnpCovariance(result->T_a_b, points_a, pixels_b, b.intrinsics);
  result->verified = true;
}

void VerifyEpipolar(const Keyframe& a, const Keyframe& b, const std::vector<cv::DMatch>& matches,
                    const VerificationOptions& options, VerificationResult* result) {
  std::vector<cv::Point2f> pa;
  std::vector<cv::Point2f> pb;
  for (const cv::DMatch& m : matches) {
    pa.push_back(a.keypoints[m.queryIdx]);
    pb.push_back(b.keypoints[m.trainIdx]);
  }
  const bool essential = HasIntrinsics(a) && HasIntrinsics(b);
  result->method = essential ? VerificationMethod::kEssential : VerificationMethod::kFundamental;
  if (static_cast<int>(matches.size()) < std::max(options.min_inliers, 8)) {
    result->reason = "matches " + std::to_string(matches.size()) + " < " + std::to_string(options.min_inliers);
    return;
  }
  std::vector<uchar> mask;
  cv::Mat R;
  cv::Mat t;
  if (essential) {
    // Normalised coordinates let the two cameras differ; the threshold scales with the focal.
    std::vector<cv::Point2f> na;
    std::vector<cv::Point2f> nb;
    cv::undistortPoints(pa, na, CameraMatrix(a.intrinsics), cv::noArray());
    cv::undistortPoints(pb, nb, CameraMatrix(b.intrinsics), cv::noArray());
    const double focal = 0.5 * (b.intrinsics.fx + b.intrinsics.fy);
    const cv::Mat E = cv::findEssentialMat(na, nb, cv::Mat::eye(3, 3, CV_64F), cv::RANSAC,
                                           options.ransac_confidence,
                                           options.epipolar_threshold_px / focal, mask);
    if (E.rows != 3 || E.cols != 3) {
      result->reason = "essential matrix RANSAC failed";
      return;
    }
    cv::recoverPose(E, na, nb, cv::Mat::eye(3, 3, CV_64F), R, t, mask);
  } else {
    const cv::Mat F = cv::findFundamentalMat(pa, pb, cv::FM_RANSAC, options.epipolar_threshold_px,
                                             options.ransac_confidence, mask);
    if (F.rows != 3 || F.cols != 3) {
      result->reason = "fundamental matrix RANSAC failed";
      return;
    }
  }
  for (size_t i = 0; i < matches.size(); ++i) {
    if (mask[i]) result->inlier_matches.push_back(matches[i]);
  }
  if (!CheckSupport(a, b, options, result)) return;
  if (!R.empty()) {
    Eigen::Matrix3d R_b_a;
    Eigen::Vector3d t_b_a;
    cv::cv2eigen(R, R_b_a);
    cv::cv2eigen(t, t_b_a);
    result->T_a_b = common::Rigid3d(t_b_a, Eigen::Quaterniond(R_b_a)).inverse();
    result->has_pose = true;
  }
  result->verified = true;
}

std::vector<cv::DMatch> MatchKeyframes(const Keyframe& a, const Keyframe& b,
                                       const VerificationOptions& options) {
  return MatchDescriptors(a.descriptors, b.descriptors, options.matching, &a.vocabulary_nodes,
                          &b.vocabulary_nodes);
}

}  // namespace

cv::Matx33d CameraMatrix(const sensor::PinholeIntrinsics& in) {
  return {in.fx, 0.0, in.cx, 0.0, in.fy, in.cy, 0.0, 0.0, 1.0};
}

common::Rigid3d FromRvecTvec(const cv::Mat& rvec, const cv::Mat& tvec) {
  const Eigen::Vector3d r(rvec.at<double>(0), rvec.at<double>(1), rvec.at<double>(2));
  const double angle = r.norm();
  const Eigen::Quaterniond q = angle > 0.0 ? Eigen::Quaterniond(Eigen::AngleAxisd(angle, r / angle))
                                           : Eigen::Quaterniond::Identity();
  return common::Rigid3d(
      Eigen::Vector3d(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2)), q);
}

void ToRvecTvec(const common::Rigid3d& pose, cv::Mat* rvec, cv::Mat* tvec) {
  const Eigen::AngleAxisd rotation(pose.rotation());
  const Eigen::Vector3d r = rotation.angle() * rotation.axis();
  const Eigen::Vector3d& t = pose.translation();
  *rvec = (cv::Mat_<double>(3, 1) << r.x(), r.y(), r.z());
  *tvec = (cv::Mat_<double>(3, 1) << t.x(), t.y(), t.z());
}

bool VerificationOptions::IsValid(std::string* error) const {
  if (min_inliers < 6 || grid_cols < 1 || grid_rows < 1 || min_occupied_cells < 0 ||
      min_occupied_cells > grid_cols * grid_rows || ransac_iterations < 1) {
    *error = "verification: min_inliers >= 6, grid and min_occupied_cells within the grid";
    return false;
  }
  if (!(pnp_threshold_px > 0.0) || !(epipolar_threshold_px > 0.0) ||
      !(ransac_confidence > 0.0 && ransac_confidence < 1.0) || !(max_mean_reprojection_px > 0.0)) {
    *error = "verification: thresholds must be positive, confidence in (0, 1)";
    return false;
  }
  return true;
}

const char* ToString(VerificationMethod method) {
  switch (method) {
    case VerificationMethod::kPnp:
      return "pnp";
    case VerificationMethod::kEssential:
      return "essential";
    case VerificationMethod::kFundamental:
      return "fundamental";
  }
  return "?";
}

VerificationResult VerifyKeyframes(const Keyframe& a, const Keyframe& b,
                                   const VerificationOptions& options) {
  VerificationResult result;
  const std::vector<cv::DMatch> matches = MatchKeyframes(a, b, options);
  result.matches = static_cast<int>(matches.size());
  if (a.has_depth() && HasIntrinsics(b)) {
    VerifyPnp(a, b, matches, options, &result);
  } else {
    VerifyEpipolar(a, b, matches, options, &result);
  }
  return result;
}

int CountMatchesExplained(const Keyframe& a, const Keyframe& b, const common::Rigid3d& T_a_b,
                          const VerificationOptions& options) {
  if (!a.has_depth() || !HasIntrinsics(b)) return 0;
  const common::Rigid3d T_b_a = T_a_b.inverse();
  int explained = 0;
  for (const cv::DMatch& m : MatchKeyframes(a, b, options)) {
    const Eigen::Vector3f& p_a = a.points_camera[m.queryIdx];
    if (!std::isfinite(p_a.z())) continue;
    const Eigen::Vector3d p_b = T_b_a * p_a.cast<double>();
    if (!(p_b.z() > 0.0)) continue;
    const cv::Point2f& pixel = b.keypoints[m.trainIdx];
    explained += (Project(b.intrinsics, p_b) - Eigen::Vector2d(pixel.x, pixel.y)).norm() <=
                 options.pnp_threshold_px;
  }
  return explained;
}

}  // namespace visual_loop
}  // namespace fusemap
