#ifndef FUSEMAP_SIM_RGBD_RENDERER_H_
#define FUSEMAP_SIM_RGBD_RENDERER_H_

#include <cstdint>
#include <string>
#include <vector>

#include "fusemap/common/config_reader.h"
#include "fusemap/common/rigid_transform.h"
#include "fusemap/sensor/rgbd_frame.h"
#include "fusemap/sim/floor_tags.h"
#include "fusemap/sim/world.h"

namespace fusemap {
namespace sim {

// A Kinect-class RGB-D camera on the robot: colour and depth share the pinhole intrinsics; the
// depth camera sits depth_baseline_m to the colour camera's left (-x of the optical frame).
struct RgbdCameraOptions {
  double rate_hz = 10.0;
  int width = 640;
  int height = 480;
  double fx = 525.0;
  double fy = 525.0;
  double cx = 319.5;
  double cy = 239.5;
  double mount_x_m = 0.15;  // Colour camera in the base frame.
  double mount_y_m = 0.0;
  double mount_z_m = 1.0;
  double pitch_down_deg = 25.0;
  double depth_baseline_m = 0.025;
  double depth_min_m = 0.2;
  double depth_max_m = 5.5;
  // Depth noise stddev = k * z^2 (Khoshelham & Elberink 2012, Kinect random error model).
  double depth_noise_k_per_m = 0.0015;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};
RgbdCameraOptions ParseRgbdCameraOptions(common::ConfigReader& reader);

sensor::PinholeIntrinsics Intrinsics(const RgbdCameraOptions& options);
common::Rigid3d TBaseColor(const RgbdCameraOptions& options);
common::Rigid3d TColorDepth(const RgbdCameraOptions& options);

// Colour (RGB8) and ideal depth along the optical axis (metres, 0 = nothing) of one pinhole
// view, by ray casting every pixel against the floor, ceiling and vertical prisms. Pure.
void RenderView(const World& world, const std::vector<Prism>& prisms, const FloorTags& tags,
                const common::Rigid3d& T_world_camera, const sensor::PinholeIntrinsics& intrinsics,
                std::vector<uint8_t>* color_rgb, std::vector<float>* depth_m);

// A complete noisy frame at T_world_base: colour from the colour camera, depth (mm, with
// range-dependent noise, range limits and dropout zones) from the depth camera. Noise is drawn
// from MakeRng(seed, kDepth, frame_index), so frames can be rendered in any order or thread.
sensor::RgbdFrame RenderRgbdFrame(const World& world, const std::vector<Prism>& prisms,
                                  const FloorTags& tags, const common::Rigid2d& T_world_base,
                                  double stamp_s, const RgbdCameraOptions& options, uint64_t seed,
                                  uint64_t frame_index);

// Applies `lighting` to an RGB8 image in place: gain, bias, then noise drawn from
// MakeRng(seed, kColor, frame_index) (so frames stay independent of rendering order); values
// are rounded and clamped to 0..255. The identity phase leaves the image untouched.
void ApplyLighting(const LightingPhase& lighting, uint64_t seed, uint64_t frame_index,
                   std::vector<uint8_t>* color_rgb);

}  // namespace sim
}  // namespace fusemap

#endif  // FUSEMAP_SIM_RGBD_RENDERER_H_
