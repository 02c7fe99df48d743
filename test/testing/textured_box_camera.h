#ifndef FUSEMAP_TEST_TESTING_TEXTURED_BOX_CAMERA_H_
#define FUSEMAP_TEST_TESTING_TEXTURED_BOX_CAMERA_H_

// An RGB-D camera in a box of textured walls, for visual loop tests: each wall carries its own
// random pattern of shapes (drawn with OpenCV, seeded), and a frame is ray cast exactly (grey
// colour image, depth in mm, same intrinsics for both). Header-only and test-only; the
// simulator's RgbdRenderer is the full-scale version.

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "fusemap/common/rigid_transform.h"
#include "fusemap/sensor/rgbd_frame.h"

namespace fusemap {
namespace test_world {

class TexturedBoxCamera {
 public:
  static constexpr double kPixelsPerM = 100.0;
  static constexpr double kWallHeightM = 2.5;
  static constexpr double kCameraHeightM = 0.5;

  // Walls of the box [x0, x1] x [y0, y1]; `seed` draws the textures.
  TexturedBoxCamera(double x0, double y0, double x1, double y1, unsigned seed) {
    const Eigen::Vector2d c00(x0, y0), c10(x1, y0), c11(x1, y1), c01(x0, y1);
    std::mt19937 rng(seed);
    for (const auto& [a, b] : {std::pair{c00, c10}, {c10, c11}, {c11, c01}, {c01, c00}}) {
      walls_.push_back({a, b, Texture((b - a).norm(), &rng)});
    }
    intrinsics_.width = 640;
    intrinsics_.height = 480;
    intrinsics_.fx = intrinsics_.fy = 500.0;
    intrinsics_.cx = 319.5;
    intrinsics_.cy = 239.5;
  }

  // The camera looks along the base's x axis from kCameraHeightM.
  static common::Rigid3d T_base_camera() {
    return common::Rigid3d(Eigen::Vector3d(0.0, 0.0, kCameraHeightM),
                           Eigen::Quaterniond(0.5, -0.5, 0.5, -0.5));
  }

  sensor::RgbdFrame Render(double stamp_s, const common::Rigid2d& T_world_base) const {
    sensor::RgbdFrame frame;
    frame.stamp_s = stamp_s;
    frame.color_intrinsics = frame.depth_intrinsics = intrinsics_;
    frame.T_base_color = T_base_camera();
    const int w = intrinsics_.width, h = intrinsics_.height;
    frame.color_rgb.assign(3 * w * h, 128);
    frame.depth_mm.assign(w * h, 0);
    const Eigen::Vector2d origin = T_world_base.translation();
    const Eigen::Rotation2Dd yaw(T_world_base.angle_rad());
    for (int v = 0; v < h; ++v) {
      for (int u = 0; u < w; ++u) {
        // Optical ray with unit depth: x right, y down, z forward → base x forward, y left, z up.
        const double xc = (u - intrinsics_.cx) / intrinsics_.fx;
        const double yc = (v - intrinsics_.cy) / intrinsics_.fy;
        const Eigen::Vector2d dir = yaw * Eigen::Vector2d(1.0, -xc);
        const double dz = -yc;
        double best_t = 1e9;
        uint8_t value = 128;
        for (const Wall& wall : walls_) {
          const Eigen::Vector2d e = wall.b - wall.a;
          const double denom = dir.x() * (-e.y()) - dir.y() * (-e.x());
          if (std::abs(denom) < 1e-12) continue;
          const Eigen::Vector2d r = wall.a - origin;
          const double t = (r.x() * (-e.y()) - r.y() * (-e.x())) / denom;
          const double s = (dir.x() * r.y() - dir.y() * r.x()) / denom;
          const double z = kCameraHeightM + t * dz;
          if (t <= 0.05 || t >= best_t || s < 0.0 || s > 1.0 || z < 0.0 || z > kWallHeightM) {
            continue;
          }
          best_t = t;
          const int col = std::min(wall.texture.cols - 1, static_cast<int>(s * e.norm() * kPixelsPerM));
          const int row = std::min(wall.texture.rows - 1,
                                   static_cast<int>((kWallHeightM - z) * kPixelsPerM));
          value = wall.texture.at<uint8_t>(row, col);
        }
        uint8_t* rgb = &frame.color_rgb[3 * (v * w + u)];
        rgb[0] = rgb[1] = rgb[2] = value;
        if (best_t < 1e8) frame.depth_mm[v * w + u] = static_cast<uint16_t>(std::lround(1e3 * best_t));
      }
    }
    return frame;
  }

 private:
  struct Wall {
    Eigen::Vector2d a, b;
    cv::Mat texture;  // CV_8UC1, kPixelsPerM, row 0 at the top of the wall
  };

  static cv::Mat Texture(double length_m, std::mt19937* rng) {
    const int cols = static_cast<int>(length_m * kPixelsPerM) + 1;
    const int rows = static_cast<int>(kWallHeightM * kPixelsPerM) + 1;
    cv::Mat texture(rows, cols, CV_8UC1, cv::Scalar(128));
    std::uniform_int_distribution<int> x(0, cols - 1), y(0, rows - 1), size(4, 30), grey(0, 255);
    for (int i = 0; i < cols * rows / 120; ++i) {
      const cv::Point p(x(*rng), y(*rng));
      const int s = size(*rng);
      if (i % 2 == 0) {
        cv::rectangle(texture, p, p + cv::Point(s, s * 2 / 3), cv::Scalar(grey(*rng)), cv::FILLED);
      } else {
        cv::circle(texture, p, s / 2, cv::Scalar(grey(*rng)), cv::FILLED);
      }
    }
    return texture;
  }

  std::vector<Wall> walls_;
  sensor::PinholeIntrinsics intrinsics_;
};

}  // namespace test_world
}  // namespace fusemap

#endif  // FUSEMAP_TEST_TESTING_TEXTURED_BOX_CAMERA_H_
