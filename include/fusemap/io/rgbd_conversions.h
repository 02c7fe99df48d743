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

// An rgbd_frame_t's images as they came on the wire: still compressed (jpeg/png16) or raw.
struct RgbdImageData {
  std::string color_encoding;
  std::vector<uint8_t> color_data;
  std::string depth_encoding;
  std::vector<uint8_t> depth_data;
};

// The cheap half of decoding, which touches no pixel (the daemon does it on the LCM handler
// thread): checks the message layout, intrinsics and transforms, and that each image's encoding
// is known and its size (read from the PNG/JPEG header, or the raw byte count) is the one the
// intrinsics declare, so no later decode can allocate more than a known camera image. Fills
// *frame without its images and *images with the image bytes.
bool DecodeRgbdFrameHeader(const void* data, int size, sensor::RgbdFrame* frame,
                           RgbdImageData* images, std::string* error);

// The costly half: decodes `images` into frame->color_rgb and frame->depth_mm (sizes from the
// frame's intrinsics, as DecodeRgbdFrameHeader filled them). Repeats the cheap checks, and
// fails on image data that cannot be decoded or decodes to another size or type than its
// header declared.
bool DecodeRgbdImages(const RgbdImageData& images, sensor::RgbdFrame* frame, std::string* error);

// Both halves. Rejects with a reason: a wrong fingerprint, truncated or trailing bytes, bad
// counts, unknown encodings, empty, zero-size or absurd images, non-finite intrinsics or
// transforms, undecodable images and images whose size differs from the intrinsics.
bool DecodeRgbdFrame(const void* data, int size, sensor::RgbdFrame* frame, std::string* error);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_RGBD_CONVERSIONS_H_
