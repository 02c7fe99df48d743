#ifndef FUSEMAP_SENSOR_RGBD_FRAME_H_
#define FUSEMAP_SENSOR_RGBD_FRAME_H_

#include <cstdint>
#include <string>
#include <vector>

#include "fusemap/common/rigid_transform.h"

namespace fusemap {
namespace sensor {

// Pinhole intrinsics (no distortion model: Kinect-class drivers publish rectified images).
struct PinholeIntrinsics {
  int width = 0;
  int height = 0;
  double fx = 0.0;
  double fy = 0.0;
  double cx = 0.0;
  double cy = 0.0;
};

// One decoded RGB-D frame. Images are row-major; colour is 8-bit RGB (3 bytes per pixel),
// depth is uint16 millimetres with 0 meaning "no measurement". The depth image has its own
// intrinsics; T_color_depth maps depth-camera coordinates into the colour camera (registration
// needs both), and T_base_color places the colour camera on the robot base (x forward, z up;
// camera optical frame: z forward, x right, y down).
struct RgbdFrame {
  double stamp_s = 0.0;
  std::string frame = "camera";
  PinholeIntrinsics color_intrinsics;
  PinholeIntrinsics depth_intrinsics;
  common::Rigid3d T_color_depth;
  common::Rigid3d T_base_color;
  std::vector<uint8_t> color_rgb;
  std::vector<uint16_t> depth_mm;
};

}  // namespace sensor
}  // namespace fusemap

#endif  // FUSEMAP_SENSOR_RGBD_FRAME_H_
