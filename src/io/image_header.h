#ifndef FUSEMAP_IO_IMAGE_HEADER_H_
#define FUSEMAP_IO_IMAGE_HEADER_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace fusemap {
namespace io {

// What a compressed image's header declares, read without decoding a pixel. OpenCV offers no
// cheap way to ask, and its decoders allocate the declared size before checking anything, so a
// corrupt or hostile header (65500 x 65500) either aborts or costs seconds and gigabytes.
struct ImageHeader {
  enum class Format { kPng, kJpeg };
  Format format = Format::kPng;
  int width = 0;
  int height = 0;
  int bit_depth = 0;  // bits per sample (PNG bit depth, JPEG sample precision)
  int channels = 0;   // samples per pixel as stored (PNG: 1 grey/palette, 2, 3 or 4; JPEG: components)
};

// Reads the PNG IHDR chunk or the JPEG's first SOFn frame header. False with a reason if the
// bytes are neither, are truncated before that header, or declare a zero size.
bool ReadImageHeader(const uint8_t* data, size_t size, ImageHeader* header, std::string* error);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_IMAGE_HEADER_H_
