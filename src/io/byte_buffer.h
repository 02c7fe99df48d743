#ifndef FUSEMAP_IO_BYTE_BUFFER_H_
#define FUSEMAP_IO_BYTE_BUFFER_H_

#include <cstdint>
#include <cstring>
#include <string>

namespace fusemap {
namespace io {

// Appends fixed-width little-endian values to a byte string, whatever the host byte order.
class ByteWriter {
 public:
  explicit ByteWriter(std::string* out) : out_(out) {}

  void U8(uint8_t v) { out_->push_back(static_cast<char>(v)); }
  void U32(uint32_t v) { Unsigned(4, v); }
  void U64(uint64_t v) { Unsigned(8, v); }
  void I32(int32_t v) { U32(static_cast<uint32_t>(v)); }
  void I64(int64_t v) { U64(static_cast<uint64_t>(v)); }
  void F32(float v) {
    uint32_t bits;
    std::memcpy(&bits, &v, sizeof(bits));
    U32(bits);
  }
  void F64(double v) {
    uint64_t bits;
    std::memcpy(&bits, &v, sizeof(bits));
    U64(bits);
  }
  void Bytes(const std::string& bytes) {
    U64(bytes.size());
    out_->append(bytes);
  }

 private:
  void Unsigned(int bytes, uint64_t v) {
    char buffer[8];
    for (int i = 0; i < bytes; ++i) buffer[i] = static_cast<char>(v >> (8 * i));
    out_->append(buffer, bytes);
  }

  std::string* out_;
};

// Reads what ByteWriter wrote from an untrusted buffer: every read is bounds-checked, and the
// first failure is kept (with its byte offset) while later reads fail too.
class ByteReader {
 public:
  ByteReader(const char* data, size_t size) : data_(data), size_(size) {}

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  size_t offset() const { return offset_; }
  size_t remaining() const { return size_ - offset_; }
  void Fail(const std::string& what) {
    if (error_.empty()) error_ = "at payload byte " + std::to_string(offset_) + ": " + what;
  }

  bool U8(uint8_t* v) {
    if (!Need(1)) return false;
    *v = static_cast<uint8_t>(data_[offset_++]);
    return true;
  }
  bool U32(uint32_t* v) { return Unsigned(4, v); }
  bool U64(uint64_t* v) { return Unsigned(8, v); }
  bool I32(int32_t* v) {
    uint32_t u = 0;
    if (!U32(&u)) return false;
    *v = static_cast<int32_t>(u);
    return true;
  }
  bool I64(int64_t* v) {
    uint64_t u = 0;
    if (!U64(&u)) return false;
    *v = static_cast<int64_t>(u);
    return true;
  }
  bool F32(float* v) {
    uint32_t bits = 0;
    if (!U32(&bits)) return false;
    std::memcpy(v, &bits, sizeof(bits));
    return true;
  }
  bool F64(double* v) {
    uint64_t bits = 0;
    if (!U64(&bits)) return false;
    std::memcpy(v, &bits, sizeof(bits));
    return true;
  }
  bool Bool(bool* v) {
    uint8_t b = 0;
    if (!U8(&b)) return false;
    if (b > 1) {
      Fail("flag is " + std::to_string(b) + ", not 0 or 1");
      return false;
    }
    *v = b == 1;
    return true;
  }
  // An element count, checked against the bytes left (each element takes at least
  // `min_element_bytes`) before anyone allocates for it.
  bool Count(size_t min_element_bytes, size_t* n) {
    uint64_t count = 0;
    if (!U64(&count)) return false;
    if (count > remaining() / (min_element_bytes == 0 ? 1 : min_element_bytes)) {
      Fail("count " + std::to_string(count) + " exceeds the " + std::to_string(remaining()) +
           " bytes left");
      return false;
    }
    *n = static_cast<size_t>(count);
    return true;
  }
  bool Bytes(std::string* bytes) {
    size_t n = 0;
    if (!Count(1, &n)) return false;
    bytes->assign(data_ + offset_, n);
    offset_ += n;
    return true;
  }
  // A view of the next n bytes (already checked by the caller with Count).
  const char* Take(size_t n) {
    if (!Need(n)) return nullptr;
    const char* p = data_ + offset_;
    offset_ += n;
    return p;
  }

 private:
  bool Need(size_t n) {
    if (!ok()) return false;
    if (n > remaining()) {
      Fail("needs " + std::to_string(n) + " bytes, " + std::to_string(remaining()) + " left");
      return false;
    }
    return true;
  }
  template <typename T>
  bool Unsigned(int bytes, T* v) {
    if (!Need(bytes)) return false;
    T value = 0;
    for (int i = 0; i < bytes; ++i) {
      value |= static_cast<T>(static_cast<uint8_t>(data_[offset_ + i])) << (8 * i);
    }
    offset_ += bytes;
    *v = value;
    return true;
  }

  const char* data_;
  size_t size_;
  size_t offset_ = 0;
  std::string error_;
};

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_BYTE_BUFFER_H_
