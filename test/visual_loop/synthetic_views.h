#ifndef FUSEMAP_TEST_VISUAL_LOOP_SYNTHETIC_VIEWS_H_
#define FUSEMAP_TEST_VISUAL_LOOP_SYNTHETIC_VIEWS_H_

// Test-only views of a textured plane with known poses: camera a looks straight at a plane at
// depth plane_depth_m; camera b's view is the exact homography of a's image for a chosen T_a_b
// (Hartley & Zisserman eq. 13.2), so PnP has a ground truth to recover.

#include <random>

#include <opencv2/imgproc.hpp>

#include "fusemap/common/rigid_transform.h"
#include "fusemap/sensor/rgbd_frame.h"

namespace fusemap {
namespace visual_loop {
namespace testing {

inline sensor::PinholeIntrinsics TestIntrinsics() {
  sensor::PinholeIntrinsics in;
  in.width = 640;
  in.height = 480;
  in.fx = in.fy = 525.0;
  in.cx = 319.5;
  in.cy = 239.5;
  return in;
}

// Random blobs and strokes of many sizes: rich in ORB corners at every pyramid level.
inline cv::Mat RandomTexture(int width, int height, uint32_t seed) {
  std::mt19937 rng(seed);
  cv::Mat image(height, width, CV_8UC1, cv::Scalar(128));
  for (int i = 0; i < 1500; ++i) {
    const cv::Point center(static_cast<int>(rng() % width), static_cast<int>(rng() % height));
    const int radius = 2 + static_cast<int>(rng() % 14);
    const cv::Scalar value(static_cast<double>(rng() % 256));
    if (rng() % 2 == 0) {
      cv::circle(image, center, radius, value, cv::FILLED);
    } else {
      cv::rectangle(image, center, center + cv::Point(radius, radius * 2), value, cv::FILLED);
    }
  }
  cv::GaussianBlur(image, image, cv::Size(3, 3), 0.8);
  return image;
}

// Image b of the plane z = depth (camera a's frame) seen from camera b at T_a_b.
inline cv::Mat WarpToView(const cv::Mat& image_a, const common::Rigid3d& T_a_b,
                          const sensor::PinholeIntrinsics& in, double plane_depth_m) {
  const common::Rigid3d T_b_a = T_a_b.inverse();
  Eigen::Matrix3d K;
  K << in.fx, 0, in.cx, 0, in.fy, in.cy, 0, 0, 1;
  const Eigen::Vector3d n(0.0, 0.0, 1.0);
  const Eigen::Matrix3d H = K *
                            (T_b_a.rotation().toRotationMatrix() +
                             T_b_a.translation() * n.transpose() / plane_depth_m) *
                            K.inverse();
  cv::Matx33d H_cv;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) H_cv(r, c) = H(r, c);
  cv::Mat image_b;
  cv::warpPerspective(image_a, image_b, H_cv, image_a.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT,
                      cv::Scalar(128));
  return image_b;
}

inline common::Rigid3d PoseFromTranslationRpy(double x, double y, double z, double roll,
                                              double pitch, double yaw) {
  const Eigen::Quaterniond q = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
  return common::Rigid3d(Eigen::Vector3d(x, y, z), q);
}

// A camera 0.1 m forward and height_m up on the base, looking along base x (optical z forward,
// x right, y down), pitched down by tilt_rad.
inline common::Rigid3d CameraMount(double height_m, double tilt_rad) {
  Eigen::Matrix3d R_base_optical;
  R_base_optical << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  const Eigen::Quaterniond tilt(Eigen::AngleAxisd(tilt_rad, Eigen::Vector3d::UnitY()));
  return common::Rigid3d(Eigen::Vector3d(0.1, 0.0, height_m), tilt * Eigen::Quaterniond(R_base_optical));
}

inline double AngleBetweenDeg(const common::Rigid3d& a, const common::Rigid3d& b) {
  return a.rotation().angularDistance(b.rotation()) * 180.0 / M_PI;
}

}  // namespace testing
}  // namespace visual_loop
}  // namespace fusemap

#endif  // FUSEMAP_TEST_VISUAL_LOOP_SYNTHETIC_VIEWS_H_
