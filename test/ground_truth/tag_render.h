#ifndef FUSEMAP_TEST_GROUND_TRUTH_TAG_RENDER_H_
#define FUSEMAP_TEST_GROUND_TRUTH_TAG_RENDER_H_

#include <apriltag/apriltag.h>
#include <apriltag/tag36h11.h>

#include <Eigen/Core>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "fusemap/common/rigid_transform.h"
#include "fusemap/ground_truth/tag_detector.h"
#include "fusemap/sensor/rgbd_frame.h"

namespace fusemap {
namespace ground_truth {
namespace testing {

// A tag36h11 tag placed at T_camera_tag in the tag frame of tag_map.h, for rendering.
struct PlacedTag {
  int id = 0;
  double size_m = 0.16;
  common::Rigid3d T_camera_tag;
};

// Renders tags into a grey image with standard pinhole intrinsics (pixel (u, v) is the centre
// of pixel column u, row v). Drawn at 4x resolution and box-filtered down, so edges carry
// sub-pixel intensity like a real camera's.
inline GreyImage RenderTags(const sensor::PinholeIntrinsics& intrinsics,
                            const std::vector<PlacedTag>& tags, uint8_t background = 170) {
  constexpr int kSuper = 4;
  cv::Mat canvas(intrinsics.height * kSuper, intrinsics.width * kSuper, CV_8UC1,
                 cv::Scalar(background));
  apriltag_family_t* family = tag36h11_create();
  for (const PlacedTag& tag : tags) {
    image_u8_t* code = apriltag_to_image(family, tag.id);
    const int n = code->width;  // 10 cells: white ring, black border ring, 6x6 data.
    cv::Mat cells(n, n, CV_8UC1);
    for (int r = 0; r < n; ++r) {
      for (int c = 0; c < n; ++c) cells.at<uint8_t>(r, c) = code->buf[r * code->stride + c];
    }
    image_u8_destroy(code);
    constexpr int kCellPx = 32;
    cv::Mat texture;
    cv::resize(cells, texture, cv::Size(n * kCellPx, n * kCellPx), 0, 0, cv::INTER_NEAREST);
    // Texture edge coordinates (a, b) in [0, n*kCellPx] -> tag frame (x right, y up), with the
    // black border (cells 1..n-1) spanning size_m.
    const double m_per_px = tag.size_m / ((n - 2) * kCellPx);
    Eigen::Matrix3d A;
    A << m_per_px, 0, -0.5 * n * kCellPx * m_per_px, 0, -m_per_px, 0.5 * n * kCellPx * m_per_px, 0,
        0, 1;
    const Eigen::Matrix3d R = tag.T_camera_tag.rotation().toRotationMatrix();
    Eigen::Matrix3d Rt;
    Rt << R.col(0), R.col(1), tag.T_camera_tag.translation();
    Eigen::Matrix3d K;
    K << intrinsics.fx * kSuper, 0, (intrinsics.cx + 0.5) * kSuper, 0, intrinsics.fy * kSuper,
        (intrinsics.cy + 0.5) * kSuper, 0, 0, 1;
    // Edge coordinates -> OpenCV's pixel-index coordinates on both sides.
    Eigen::Matrix3d to_index = Eigen::Matrix3d::Identity();
    to_index(0, 2) = to_index(1, 2) = -0.5;
    const Eigen::Matrix3d H = to_index * K * Rt * A * to_index.inverse();
    cv::Mat H_cv;
    cv::eigen2cv(H, H_cv);
    cv::Mat mask(texture.size(), CV_8UC1, cv::Scalar(255));
    cv::Mat warped, warped_mask;
    cv::warpPerspective(texture, warped, H_cv, canvas.size(), cv::INTER_LINEAR);
    cv::warpPerspective(mask, warped_mask, H_cv, canvas.size(), cv::INTER_NEAREST);
    warped.copyTo(canvas, warped_mask);
  }
  tag36h11_destroy(family);
  cv::Mat small;
  cv::resize(canvas, small, cv::Size(intrinsics.width, intrinsics.height), 0, 0, cv::INTER_AREA);
  GreyImage image;
  image.width = small.cols;
  image.height = small.rows;
  image.pixels.assign(small.data, small.data + small.total());
  return image;
}

}  // namespace testing
}  // namespace ground_truth
}  // namespace fusemap

#endif  // FUSEMAP_TEST_GROUND_TRUTH_TAG_RENDER_H_
