#include "fusemap/sim/rgbd_renderer.h"

#include <apriltag/apriltag.h>
#include <apriltag/tag36h11.h>
#include <gtest/gtest.h>

#include <cmath>

namespace fusemap {
namespace sim {
namespace {

// An empty room except for one floor tag in front of the robot at the origin.
World TagWorld(const FloorTag& tag) {
  World world;
  world.ceiling_height_m = 3.0;
  world.tags = {tag};
  Prism wall;  // Far wall at x = 8 so the upper image is not empty.
  wall.centre_m = Eigen::Vector2d(8.0, 0.0);
  wall.half_size_m = Eigen::Vector2d(0.1, 10.0);
  wall.z_max_m = 3.0;
  world.prisms = {wall};
  return world;
}

Eigen::Vector2d Project(const common::Rigid3d& T_world_camera, const sensor::PinholeIntrinsics& k,
                        const Eigen::Vector3d& p_world) {
  const Eigen::Vector3d p = T_world_camera.inverse() * p_world;
  return Eigen::Vector2d(k.fx * p.x() / p.z() + k.cx, k.fy * p.y() / p.z() + k.cy);
}

// Detects tag36h11 tags in an RGB image; returns (id, corners) of each detection.
std::vector<std::pair<int, std::array<Eigen::Vector2d, 4>>> Detect(const std::vector<uint8_t>& rgb,
                                                                   int width, int height) {
  apriltag_family_t* family = tag36h11_create();
  apriltag_detector_t* detector = apriltag_detector_create();
  apriltag_detector_add_family(detector, family);
  detector->quad_decimate = 1.0;
  detector->nthreads = 1;
  image_u8_t* gray = image_u8_create(width, height);
  for (int v = 0; v < height; ++v) {
    for (int u = 0; u < width; ++u) {
      const uint8_t* c = &rgb[3 * (v * width + u)];
      gray->buf[v * gray->stride + u] = static_cast<uint8_t>((c[0] + c[1] + c[2]) / 3);
    }
  }
  zarray_t* detections = apriltag_detector_detect(detector, gray);
  std::vector<std::pair<int, std::array<Eigen::Vector2d, 4>>> result;
  for (int i = 0; i < zarray_size(detections); ++i) {
    apriltag_detection_t* det;
    zarray_get(detections, i, &det);
    std::array<Eigen::Vector2d, 4> corners;
    for (int j = 0; j < 4; ++j) corners[j] = Eigen::Vector2d(det->p[j][0], det->p[j][1]);
    result.emplace_back(det->id, corners);
  }
  apriltag_detections_destroy(detections);
  image_u8_destroy(gray);
  apriltag_detector_destroy(detector);
  tag36h11_destroy(family);
  return result;
}

void ExpectTagDetected(const FloorTag& tag, double max_corner_error_px) {
  const World world = TagWorld(tag);
  FloorTags tags;
  std::string error;
  ASSERT_TRUE(tags.Init(world.tags, &error)) << error;
  const RgbdCameraOptions options;
  const sensor::PinholeIntrinsics k = Intrinsics(options);
  const common::Rigid3d T_world_color = TBaseColor(options);  // Robot at the origin.
  std::vector<uint8_t> rgb;
  RenderView(world, world.prisms, tags, T_world_color, k, &rgb, nullptr);
  const auto detections = Detect(rgb, k.width, k.height);
  ASSERT_EQ(detections.size(), 1u) << "tag at " << tag.x_m << ", " << tag.y_m;
  EXPECT_EQ(detections[0].first, tag.id);
  // Every corner of the black square must match some detected corner. The renderer treats
  // integer pixel coordinates as pixel centres; apriltag reports corners with pixel centres at
  // +0.5, hence the shift.
  const double c = std::cos(tag.yaw_rad), s = std::sin(tag.yaw_rad), h = 0.5 * tag.size_m;
  for (const Eigen::Vector2d& corner : {Eigen::Vector2d(-h, -h), Eigen::Vector2d(h, -h),
                                        Eigen::Vector2d(h, h), Eigen::Vector2d(-h, h)}) {
    const Eigen::Vector3d p_world(tag.x_m + c * corner.x() - s * corner.y(),
                                  tag.y_m + s * corner.x() + c * corner.y(), 0.0);
    const Eigen::Vector2d truth = Project(T_world_color, k, p_world) + Eigen::Vector2d(0.5, 0.5);
    double best = 1e9;
    for (const Eigen::Vector2d& detected : detections[0].second) best = std::min(best, (detected - truth).norm());
    EXPECT_LT(best, max_corner_error_px) << "corner " << corner.transpose() << " truth " << truth.transpose();
  }
}

TEST(RgbdRendererTest, FloorTagDetectedWithAccurateCorners) {
  ExpectTagDetected(FloorTag{17, 2.2, 0.1, 0.3, 0.45}, 1.0);
}

TEST(RgbdRendererTest, FloorTagDetectedAtFourMetres) {
  ExpectTagDetected(FloorTag{5, 4.0, -0.3, 1.2, 0.45}, 1.0);
}

TEST(RgbdRendererTest, DepthOfFlatFloorAndWall) {
  World world = TagWorld(FloorTag{0, 50.0, 50.0, 0.0, 0.4});  // Tag far outside the view.
  FloorTags tags;
  std::string error;
  ASSERT_TRUE(tags.Init(world.tags, &error)) << error;
  RgbdCameraOptions options;
  options.depth_noise_k_per_m = 0.0;
  const sensor::RgbdFrame frame =
      RenderRgbdFrame(world, world.prisms, tags, common::Rigid2d::Identity(), 0.0, options, 1, 0);
  const sensor::PinholeIntrinsics& k = frame.depth_intrinsics;
  ASSERT_EQ(frame.depth_mm.size(), static_cast<size_t>(k.width * k.height));
  ASSERT_EQ(frame.color_rgb.size(), static_cast<size_t>(3 * k.width * k.height));
  const common::Rigid3d T_world_depth = frame.T_base_color * frame.T_color_depth;
  const Eigen::Matrix3d R = T_world_depth.rotation().toRotationMatrix();
  const Eigen::Vector3d o = T_world_depth.translation();
  // Floor (bottom row) and wall (top row): analytic depth along the optical axis, to 1 mm
  // (quantisation 0.5 mm plus float rounding).
  for (int v : {k.height - 1, 0}) {
    for (int u : {0, k.width / 2, k.width - 1}) {
      const Eigen::Vector3d d = R * Eigen::Vector3d((u - k.cx) / k.fx, (v - k.cy) / k.fy, 1.0);
      const double lambda = v == 0 ? (7.9 - o.x()) / d.x() : -o.z() / d.z();
      ASSERT_GT(lambda, 0.0);
      const uint16_t expected = lambda <= options.depth_max_m ? static_cast<uint16_t>(std::lround(lambda * 1000)) : 0;
      EXPECT_NEAR(frame.depth_mm[v * k.width + u], expected, 1.0) << "pixel " << u << ", " << v;
    }
  }
}

TEST(RgbdRendererTest, LightingScalesShiftsAndAddsSeededNoise) {
  const std::vector<uint8_t> image = {0, 10, 100, 200, 250, 255};
  std::vector<uint8_t> same = image;
  ApplyLighting(LightingPhase(), 1, 0, &same);
  EXPECT_EQ(same, image);  // the identity phase leaves frames as rendered
  std::vector<uint8_t> darker = image;
  ApplyLighting(LightingPhase{0.0, 0.5, 10.0, 0.0}, 1, 0, &darker);
  EXPECT_EQ(darker, (std::vector<uint8_t>{10, 15, 60, 110, 135, 138}));
  std::vector<uint8_t> grey(3 * 64 * 64, 128), a = grey, b = grey, c = grey;
  const LightingPhase noisy{0.0, 1.0, 0.0, 8.0};
  ApplyLighting(noisy, 1, 5, &a);
  ApplyLighting(noisy, 1, 5, &b);
  ApplyLighting(noisy, 1, 6, &c);
  EXPECT_EQ(a, b);  // per frame seed: independent of rendering order
  EXPECT_NE(a, c);
  double sum = 0.0, sum_sq = 0.0;
  for (uint8_t v : a) {
    sum += v - 128.0;
    sum_sq += (v - 128.0) * (v - 128.0);
  }
  EXPECT_NEAR(sum / a.size(), 0.0, 0.3);
  EXPECT_NEAR(std::sqrt(sum_sq / a.size()), 8.0, 0.3);
}

}  // namespace
}  // namespace sim
}  // namespace fusemap
