#include "fusemap/visual_loop/patch_alignment.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <vector>

#include "fusemap/visual_loop/pose_covariance.h"

namespace fusemap {
namespace visual_loop {
namespace {

// Bilinear grey value at (x, y); false within a pixel of the border (as SampleWithGradient).
bool Sample(const cv::Mat& gray, double x, double y, double* value) {
  if (!(x >= 1.0 && y >= 1.0 && x < gray.cols - 2.0 && y < gray.rows - 2.0)) return false;
  const int x0 = static_cast<int>(x);
  const int y0 = static_cast<int>(y);
  const double fx = x - x0;
  const double fy = y - y0;
  const uint8_t* row0 = gray.ptr<uint8_t>(y0) + x0;
  const uint8_t* row1 = gray.ptr<uint8_t>(y0 + 1) + x0;
  *value = (1.0 - fy) * ((1.0 - fx) * row0[0] + fx * row0[1]) +
           fy * ((1.0 - fx) * row1[0] + fx * row1[1]);
  return true;
}

// Bilinear grey value at p and its gradient (central differences one pixel either side, each
// bilinear too); false within a pixel of the border. The five values share one 4 x 4
// neighbourhood and its interpolation weights: this runs ~10^5 times a motion link.
bool SampleWithGradient(const cv::Mat& gray, const Eigen::Vector2d& p, double* value,
                        Eigen::Vector2d* gradient) {
  if (!(p.x() >= 1.0 && p.y() >= 1.0 && p.x() < gray.cols - 2.0 && p.y() < gray.rows - 2.0)) {
    return false;
  }
  const int x0 = static_cast<int>(p.x());
  const int y0 = static_cast<int>(p.y());
  const double fx = p.x() - x0;
  const double fy = p.y() - y0;
  // Rows y0 - 1 .. y0 + 2, columns x0 - 1 .. x0 + 2.
  double v[4][4];
  for (int r = 0; r < 4; ++r) {
    const uint8_t* row = gray.ptr<uint8_t>(y0 - 1 + r) + x0 - 1;
    for (int c = 0; c < 4; ++c) v[r][c] = row[c];
  }
  // Interpolated at column offset c (0: x0 - 1) along rows r and r + 1.
  const auto at = [&](int r, int c) {
    return (1.0 - fy) * ((1.0 - fx) * v[r][c] + fx * v[r][c + 1]) +
           fy * ((1.0 - fx) * v[r + 1][c] + fx * v[r + 1][c + 1]);
  };
  *value = at(1, 1);
  *gradient = Eigen::Vector2d(0.5 * (at(1, 2) - at(1, 0)), 0.5 * (at(2, 1) - at(0, 1)));
  return true;
}

Eigen::Vector3d Ray(const sensor::PinholeIntrinsics& in, const Eigen::Vector2d& pixel) {
  return Eigen::Vector3d((pixel.x() - in.cx) / in.fx, (pixel.y() - in.cy) / in.fy, 1.0);
}

// The normal of the surface around point_a, fitted to a's depth; the ray's direction where the
// depth there does not hold a plane (too few pixels on the point's own surface).
Eigen::Vector3d SurfaceNormal(const CameraImage& a, const Eigen::Vector2d& pixel_a,
                              const Eigen::Vector3d& point_a, int half_window) {
  const Eigen::Vector3d fallback = Ray(a.intrinsics, pixel_a).normalized();
  if (a.depth_m.empty()) return fallback;
  const int u0 = static_cast<int>(std::lround(pixel_a.x()));
  const int v0 = static_cast<int>(std::lround(pixel_a.y()));
  // Pixels further in depth than this from the point belong to another surface.
  const double max_depth_step_m = 0.1 * point_a.z();
  std::vector<Eigen::Vector3d> points;
  for (int v = v0 - half_window; v <= v0 + half_window; ++v) {
    if (v < 0 || v >= a.depth_m.rows) continue;
    const float* row = a.depth_m.ptr<float>(v);
    for (int u = u0 - half_window; u <= u0 + half_window; ++u) {
      if (u < 0 || u >= a.depth_m.cols) continue;
      const double z = row[u];
      if (!(z > 0.0) || std::abs(z - point_a.z()) > max_depth_step_m) continue;
      points.push_back(z * Ray(a.intrinsics, Eigen::Vector2d(u, v)));
    }
  }
  if (points.size() < 16) return fallback;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : points) scatter += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
  // A patch too small or too noisy to tell a plane from a line gives no normal.
  if (!(solver.eigenvalues()(1) > 4.0 * solver.eigenvalues()(0))) return fallback;
  return solver.eigenvectors().col(0);
}

}  // namespace

bool PatchAlignmentOptions::IsValid(std::string* error) const {
  if (half_window_px < 2 || plane_half_window_px < 2 || max_iterations < 1 || min_points < 6 ||
      max_points < min_points || !(max_shift_px > 0.0) || !(min_gradient >= 0.0)) {
    *error =
        "patch alignment: windows >= 2 px, max_iterations >= 1, 6 <= min_points <= max_points, "
        "max_shift_px > 0";
    return false;
  }
  return true;
}

std::optional<Eigen::Vector2d> AlignPatch(const CameraImage& a, const CameraImage& b,
                                          const common::Rigid3d& T_b_a,
                                          const Eigen::Vector2d& pixel_a,
                                          const Eigen::Vector3d& point_a,
                                          const Eigen::Vector2d& keypoint_b,
                                          const PatchAlignmentOptions& options) {
  // The patch's pixels lie on the plane through point_a with the surface's normal; each is
  // carried into b by the pose.
  const Eigen::Vector3d normal = SurfaceNormal(a, pixel_a, point_a, options.plane_half_window_px);
  const double plane_offset = normal.dot(point_a);
  const int h = options.half_window_px;
  const int n = (2 * h + 1) * (2 * h + 1);
  std::vector<double> template_a(n);
  std::vector<Eigen::Vector2d> warped(n);
  int k = 0;
  for (int j = -h; j <= h; ++j) {
    for (int i = -h; i <= h; ++i, ++k) {
      const Eigen::Vector2d pixel = pixel_a + Eigen::Vector2d(i, j);
      if (!Sample(a.gray, pixel.x(), pixel.y(), &template_a[k])) return std::nullopt;
      const Eigen::Vector3d ray = Ray(a.intrinsics, pixel);
      const double along = normal.dot(ray);
      if (std::abs(along) < 1e-6) return std::nullopt;
      const Eigen::Vector3d in_b = T_b_a * ((plane_offset / along) * ray);
      if (!(in_b.z() > 0.0)) return std::nullopt;
      warped[k] = Project(b.intrinsics, in_b);
    }
  }
  const Eigen::Vector3d centre_b = T_b_a * point_a;
  if (!(centre_b.z() > 0.0)) return std::nullopt;
  const Eigen::Vector2d predicted_b = Project(b.intrinsics, centre_b);

  // Gauss-Newton on the shift in b and the grey levels' gain and offset between the views,
  // from the descriptor match's keypoint: it is within a pixel of the point, closer than the
  // pose's prediction can be, and the alignment's reach is about a pixel on sharp texture.
  Eigen::Vector2d shift = keypoint_b - predicted_b;
  double gain = 1.0;
  double offset = 0.0;
  bool converged = false;
  for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
    Eigen::Matrix4d hessian = Eigen::Matrix4d::Zero();
    Eigen::Vector4d gradient = Eigen::Vector4d::Zero();
    for (k = 0; k < n; ++k) {
      double value;
      Eigen::Vector2d image_gradient;
      if (!SampleWithGradient(b.gray, warped[k] + shift, &value, &image_gradient)) {
        return std::nullopt;
      }
      const Eigen::Vector4d jacobian(image_gradient.x(), image_gradient.y(), -template_a[k], -1.0);
      const double residual = value - (gain * template_a[k] + offset);
      hessian += jacobian * jacobian.transpose();
      gradient += jacobian * residual;
    }
    if (iteration == 0) {
      // The shift's block of the Hessian is the patch's structure tensor (sum of g g^T).
      const Eigen::Matrix2d structure = hessian.topLeftCorner<2, 2>() / n;
      const double weakest =
          Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(structure).eigenvalues()(0);
      if (!(weakest >= options.min_gradient * options.min_gradient)) return std::nullopt;
    }
    const Eigen::Vector4d step = hessian.ldlt().solve(-gradient);
    if (!step.allFinite()) return std::nullopt;
    shift += step.head<2>();
    gain += step(2);
    offset += step(3);
    if ((predicted_b + shift - keypoint_b).norm() > 2.0 * options.max_shift_px) return std::nullopt;
    if (step.head<2>().norm() < 1e-2) {
      converged = true;
      break;
    }
  }
  if (!converged) return std::nullopt;
  const Eigen::Vector2d aligned = predicted_b + shift;
  if ((aligned - keypoint_b).norm() > options.max_shift_px) return std::nullopt;
  return aligned;
}

int RefineByPatchAlignment(const Keyframe& a, const CameraImage& image_a, const Keyframe& b,
                           const CameraImage& image_b, const PatchAlignmentOptions& options,
                           VerificationResult* result) {
  if (!result->verified || !result->metric) return 0;
  const common::Rigid3d T_b_a = result->T_a_b.inverse();
  std::vector<cv::Point3f> object;
  std::vector<cv::Point2f> image;
  std::vector<Eigen::Vector3d> points_a;
  // Every stride-th inlier, so that at most max_points are aligned, spread as the inliers are.
  const int num_inliers = static_cast<int>(result->inlier_matches.size());
  const int stride = (num_inliers + options.max_points - 1) / options.max_points;
  for (int i = 0; i < num_inliers; i += stride) {
    const cv::DMatch& m = result->inlier_matches[i];
    const Eigen::Vector3f& p = a.points_camera[m.queryIdx];
    if (!std::isfinite(p.z())) continue;
    const cv::Point2f& pixel_a = a.keypoints[m.queryIdx];
    const cv::Point2f& keypoint_b = b.keypoints[m.trainIdx];
    const std::optional<Eigen::Vector2d> aligned =
        AlignPatch(image_a, image_b, T_b_a, Eigen::Vector2d(pixel_a.x, pixel_a.y), p.cast<double>(),
                   Eigen::Vector2d(keypoint_b.x, keypoint_b.y), options);
    if (!aligned) continue;
    object.emplace_back(p.x(), p.y(), p.z());
    image.emplace_back(static_cast<float>(aligned->x()), static_cast<float>(aligned->y()));
    points_a.push_back(p.cast<double>());
  }
  const int aligned_points = static_cast<int>(object.size());
  if (aligned_points < std::max(options.min_points, 6)) return aligned_points;
  cv::Mat rvec;
  cv::Mat tvec;
  ToRvecTvec(T_b_a, &rvec, &tvec);
  cv::solvePnPRefineLM(object, image, CameraMatrix(b.intrinsics), cv::noArray(), rvec, tvec);
  const common::Rigid3d refined_T_b_a = FromRvecTvec(rvec, tvec);
  std::vector<Eigen::Vector2d> pixels_b;
  for (const cv::Point2f& pixel : image) pixels_b.emplace_back(pixel.x, pixel.y);
  result->T_a_b = refined_T_b_a.inverse();
  result->mean_reprojection_px =
      MeanReprojectionPx(refined_T_b_a, points_a, pixels_b, b.intrinsics);
  result->covariance = PnpCovariance(result->T_a_b, points_a, pixels_b, b.intrinsics);
  return aligned_points;
}

}  // namespace visual_loop
}  // namespace fusemap
