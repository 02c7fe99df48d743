#ifndef FUSEMAP_IO_LCM_WIRE_H_
#define FUSEMAP_IO_LCM_WIRE_H_

// Internal to io: the checked LCM wire reading and the encode helper shared by the LCM
// conversion units. Only .cc files in src/io (and io's tests) include this.

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "fusemap/io/lcm_conversions.h"

namespace fusemap {
namespace io {
namespace lcm_wire {

// Walks the big-endian LCM wire layout with bounds checks. The generated decoders trust
// length fields (a negative count becomes a huge resize), so every count is checked here first.
class WireCursor {
 public:
  WireCursor(const void* data, int size)
      : data_(static_cast<const uint8_t*>(data)), size_(data == nullptr ? 0 : size) {}

  bool ReadInt64(int64_t* value) {
    if (size_ - pos_ < 8) return false;
    uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v = (v << 8) | data_[pos_ + i];
    pos_ += 8;
    *value = static_cast<int64_t>(v);
    return true;
  }
  bool ReadInt32(int32_t* value) {
    if (size_ - pos_ < 4) return false;
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v = (v << 8) | data_[pos_ + i];
    pos_ += 4;
    *value = static_cast<int32_t>(v);
    return true;
  }
  bool Skip(int64_t bytes) {
    if (bytes < 0 || size_ - pos_ < bytes) return false;
    pos_ += static_cast<int>(bytes);
    return true;
  }
  // An LCM string: int32 length counting the terminating NUL (so at least 1), then the bytes.
  bool SkipString() {
    int32_t length = 0;
    return ReadInt32(&length) && length >= 1 && Skip(length);
  }
  // A counted byte array: int32 length, then the bytes.
  bool SkipBytes() {
    int32_t length = 0;
    return ReadInt32(&length) && Skip(length);
  }
  // A counted float array: the count must be in [0, kMaxLaserBeams].
  bool SkipFloatArray(const char* name, int32_t* count, std::string* error) {
    if (!ReadInt32(count)) return Fail(std::string("truncated before ") + name, error);
    if (*count < 0 || *count > kMaxLaserBeams) {
      return Fail(std::string("absurd ") + name + " " + std::to_string(*count), error);
    }
    if (!Skip(4 * static_cast<int64_t>(*count))) {
      return Fail(std::string("truncated in ") + name, error);
    }
    return true;
  }
  bool AtEnd(std::string* error) const {
    if (pos_ != size_) {
      return Fail(std::to_string(size_ - pos_) + " trailing bytes after message", error);
    }
    return true;
  }
  static bool Fail(const std::string& reason, std::string* error) {
    if (error != nullptr) *error = reason;
    return false;
  }

 private:
  const uint8_t* data_;
  int size_;
  int pos_ = 0;
};

template <class Msg>
std::vector<uint8_t> Encode(const Msg& msg) {
  std::vector<uint8_t> bytes(msg.getEncodedSize());
  const int n = msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  (void)n;
  return bytes;
}

// Decodes a fixed-layout message after checking fingerprint and exact size.
template <class Msg>
bool DecodeFixed(const void* data, int size, Msg* msg, std::string* error) {
  WireCursor cursor(data, size);
  int64_t hash = 0;
  if (!cursor.ReadInt64(&hash)) return WireCursor::Fail("truncated fingerprint", error);
  if (hash != Msg::getHash()) {
    return WireCursor::Fail(std::string("fingerprint is not ") + Msg::getTypeName(), error);
  }
  if (size != msg->getEncodedSize()) {
    return WireCursor::Fail(std::string(Msg::getTypeName()) + " must be " +
                                std::to_string(msg->getEncodedSize()) + " bytes, got " +
                                std::to_string(size),
                            error);
  }
  if (msg->decode(data, 0, size) != size) return WireCursor::Fail("decode failed", error);
  return true;
}

inline bool AllFinite(const double* v, int n) {
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(v[i])) return false;
  }
  return true;
}

}  // namespace lcm_wire
}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_LCM_WIRE_H_
