#ifndef FUSEMAP_TEST_TESTING_WALL_FRAME_H_
#define FUSEMAP_TEST_TESTING_WALL_FRAME_H_

#include <Eigen/Geometry>
#include <cstdint>

#include "fusemap/sensor/rgbd_frame.h"

namespace fusemap {
namespace test_world {

constexpr double kWallFrameDepthM = 2.0;

// A small grey RGB-D frame from a camera looking along the base's +x axis at a flat wall
// kWallFrameDepthM ahead (depth and colour cameras coincide).
inline sensor::RgbdFrame WallFrame(double stamp_s) {
  sensor::RgbdFrame frame;
  frame.stamp_s = stamp_s;
  sensor::PinholeIntrinsics k;
  k.width = 64;
  k.height = 48;
  k.fx = k.fy = 50.0;
  k.cx = 31.5;
  k.cy = 23.5;
  frame.color_intrinsics = frame.depth_intrinsics = k;
  Eigen::Matrix3d R_base_optical;
  R_base_optical << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  frame.T_base_color = common::Rigid3d(Eigen::Vector3d::Zero(), Eigen::Quaterniond(R_base_optical));
  frame.color_rgb.assign(3 * k.width * k.height, 128);
  frame.depth_mm.assign(k.width * k.height, static_cast<uint16_t>(kWallFrameDepthM * 1000.0));
  return frame;
}

}  // namespace test_world
}  // namespace fusemap

#endif  // FUSEMAP_TEST_TESTING_WALL_FRAME_H_
