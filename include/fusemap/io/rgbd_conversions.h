#ifndef FUSEMAP_IO_RGBD_CONVERSIONS_H_
#define FUSEMAP_IO_RGBD_CONVERSIONS_H_

#include <cstdint>
#include <string>
#include <vector>

#include "fusemap/sensor/rgbd_frame.h"

namespace fusemap {
namespace io {

// Largest accepted image side: anything beyond is a corrupt header, not a camera.
constexpr int kMaxImageSide = 8192;

// How sensor::RgbdFrame images go on the wire (fusemap_lcm::rgbd_frame_t).
struct RgbdEncodeOptions {
  std::string color_encoding = "jpeg";  // "jpeg" or "rgb8" (raw).
  int jpeg_quality = 90;                // 1..100
  std::string depth_encoding = "png16";  // "png16" or "mono16" (raw little-endian).
  int png_compression = 1;               // 0..9; low is much faster and only slightly larger.

  bool IsValid(std::string* error) const;
};

// Encodes `frame` as fusemap_lcm::rgbd_frame_t bytes. Fails (false, *error) if the image
// buffers do not match the intrinsics or the options are invalid.
bool EncodeRgbdFrame(const sensor::RgbdFrame& frame, const RgbdEncodeOptions& options,
                     std::vector<uint8_t>* bytes, std::string* error);

// Decodes rgbd_frame_t bytes. Rejects with a reason: a wrong fingerprint, truncated or trailing
// bytes, bad counts, unknown encodings, zero or absurd image sizes, non-finite intrinsics or
// transforms, undecodable images and images whose size differs from the intrinsics.
bool DecodeRgbdFrame(const void* data, int size, sensor::RgbdFrame* frame, std::string* error);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_RGBD_CONVERSIONS_H_
