#include "image_header.h"

#include <cstring>

namespace fusemap {
namespace io {
namespace {

bool Fail(const std::string& reason, std::string* error) {
  *error = reason;
  return false;
}

uint32_t BigEndian32(const uint8_t* p) {
  return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | p[3];
}

int BigEndian16(const uint8_t* p) { return (p[0] << 8) | p[1]; }

// PNG specification, sec. 5.2 (signature) and 11.2.2 (IHDR: width, height, bit depth, colour
// type, ...); the IHDR chunk must come first.
bool ReadPngHeader(const uint8_t* data, size_t size, ImageHeader* header, std::string* error) {
  if (size < 8 + 8 + 13) return Fail("PNG truncated before its IHDR chunk", error);
  if (BigEndian32(data + 8) != 13 || std::memcmp(data + 12, "IHDR", 4) != 0) {
    return Fail("PNG does not start with an IHDR chunk", error);
  }
  const uint32_t width = BigEndian32(data + 16);
  const uint32_t height = BigEndian32(data + 20);
  // The specification limits both to 2^31 - 1; larger values are corrupt.
  if (width == 0 || height == 0 || width > 0x7fffffffu || height > 0x7fffffffu) {
    return Fail("PNG declares an invalid size", error);
  }
  int channels = 0;
  switch (data[25]) {
    case 0: channels = 1; break;  // greyscale
    case 2: channels = 3; break;  // RGB
    case 3: channels = 1; break;  // palette index
    case 4: channels = 2; break;  // greyscale + alpha
    case 6: channels = 4; break;  // RGBA
    default: return Fail("PNG declares an unknown colour type", error);
  }
  header->format = ImageHeader::Format::kPng;
  header->width = static_cast<int>(width);
  header->height = static_cast<int>(height);
  header->bit_depth = data[24];
  header->channels = channels;
  return true;
}

bool IsStartOfFrame(int marker) {
  // SOF0..SOF15 are 0xC0..0xCF except DHT (C4), JPG (C8) and DAC (CC).
  return marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
}

// ITU T.81, B.1.1 (markers) and B.2.2 (frame header: P, Y, X, Nf): walks the marker segments
// up to the first SOFn.
bool ReadJpegHeader(const uint8_t* data, size_t size, ImageHeader* header, std::string* error) {
  size_t pos = 2;  // after SOI
  while (true) {
    // Any number of 0xFF fill bytes may precede a marker.
    if (pos >= size || data[pos] != 0xFF) return Fail("JPEG has no frame header (SOF)", error);
    while (pos < size && data[pos] == 0xFF) ++pos;
    if (pos >= size) return Fail("JPEG truncated before its frame header", error);
    const int marker = data[pos++];
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD8)) continue;  // no length field
    if (marker == 0xD9 || marker == 0xDA) return Fail("JPEG has no frame header (SOF)", error);
    if (size - pos < 2) return Fail("JPEG truncated in a marker segment", error);
    const size_t length = static_cast<size_t>(BigEndian16(data + pos));
    if (length < 2 || size - pos < length) return Fail("JPEG marker segment runs past the end", error);
    if (IsStartOfFrame(marker)) {
      if (length < 8) return Fail("JPEG frame header too short", error);
      header->format = ImageHeader::Format::kJpeg;
      header->bit_depth = data[pos + 2];
      header->height = BigEndian16(data + pos + 3);
      header->width = BigEndian16(data + pos + 5);
      header->channels = data[pos + 7];
      // A zero height would be defined later by a DNL marker; no camera writes that.
      if (header->width == 0 || header->height == 0) return Fail("JPEG declares a zero size", error);
      return true;
    }
    pos += length;
  }
}

}  // namespace

bool ReadImageHeader(const uint8_t* data, size_t size, ImageHeader* header, std::string* error) {
  static const uint8_t kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (data == nullptr || size == 0) return Fail("image is empty", error);
  if (size >= 8 && std::memcmp(data, kPngSignature, 8) == 0) {
    return ReadPngHeader(data, size, header, error);
  }
  if (size >= 2 && data[0] == 0xFF && data[1] == 0xD8) return ReadJpegHeader(data, size, header, error);
  return Fail("image is neither PNG nor JPEG", error);
}

}  // namespace io
}  // namespace fusemap
