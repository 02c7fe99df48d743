#include "submap_state_codec.h"

#include <zlib.h>

#include <cmath>
#include <string>

namespace fusemap {
namespace io {

void EncodeRigid2d(const common::Rigid2d& T, ByteWriter* out) {
  out->F64(T.x());
  out->F64(T.y());
  out->F64(T.angle_rad());
}

bool DecodeRigid2d(ByteReader* in, common::Rigid2d* T) {
  double x = 0, y = 0, angle = 0;
  if (!in->F64(&x) || !in->F64(&y) || !in->F64(&angle)) return false;
  *T = common::Rigid2d(x, y, angle);
  return true;
}

void EncodeTimedPose2d(double stamp_s, const common::Rigid2d& pose, ByteWriter* out) {
  out->F64(stamp_s);
  EncodeRigid2d(pose, out);
}

bool DecodeTimedPose2d(ByteReader* in, double* stamp_s, common::Rigid2d* pose) {
  if (!in->F64(stamp_s) || !DecodeRigid2d(in, pose)) return false;
  if (!std::isfinite(*stamp_s) || !std::isfinite(pose->x()) || !std::isfinite(pose->y()) ||
      !std::isfinite(pose->angle_rad())) {
    in->Fail("a stamp or pose is not finite");
    return false;
  }
  return true;
}

namespace {

enum GridEncoding : uint8_t { kRawCells = 0, kZlibCells = 1 };
// zlib's best case is about 1032:1 (deflate's limit); a larger claimed ratio is corruption.
constexpr uint64_t kMaxZlibRatio = 1032;
// No submap grid comes near this (16384 x 16384 cells at 5 cm is 820 m square).
constexpr uint64_t kMaxGridCells = uint64_t{1} << 28;

}  // namespace

void EncodeSubmapState(const mapping::SubmapState2D& submap, bool compress, ByteWriter* out) {
  EncodeRigid2d(submap.T_local_submap, out);
  out->F64(submap.limits.resolution_m);
  out->F64(submap.limits.origin_m.x());
  out->F64(submap.limits.origin_m.y());
  out->I32(submap.limits.num_x_cells);
  out->I32(submap.limits.num_y_cells);
  out->I32(submap.num_range_data);
  out->U8(submap.finished ? 1 : 0);
  std::string raw(2 * submap.cells.size(), '\0');
  for (size_t i = 0; i < submap.cells.size(); ++i) {
    raw[2 * i] = static_cast<char>(submap.cells[i] & 0xff);
    raw[2 * i + 1] = static_cast<char>(submap.cells[i] >> 8);
  }
  if (!compress) {
    out->U8(kRawCells);
    out->Bytes(raw);
    return;
  }
  uLongf size = compressBound(raw.size());
  std::string packed(size, '\0');
  // Level 1: grids are mostly unknown or saturated cells and compress well even so; the
  // checkpoint is written every few seconds by the mapping thread.
  const int rc = compress2(reinterpret_cast<Bytef*>(&packed[0]), &size,
                           reinterpret_cast<const Bytef*>(raw.data()), raw.size(), 1);
  if (rc != Z_OK) {  // cannot happen with compressBound's size; stay correct anyway
    out->U8(kRawCells);
    out->Bytes(raw);
    return;
  }
  packed.resize(size);
  out->U8(kZlibCells);
  out->Bytes(packed);
}

bool DecodeSubmapState(ByteReader* in, mapping::SubmapState2D* submap) {
  double ox = 0, oy = 0;
  int32_t nx = 0, ny = 0, num_range_data = 0;
  uint8_t encoding = 0;
  std::string stored;
  if (!DecodeRigid2d(in, &submap->T_local_submap) || !in->F64(&submap->limits.resolution_m) ||
      !in->F64(&ox) || !in->F64(&oy) || !in->I32(&nx) || !in->I32(&ny) ||
      !in->I32(&num_range_data) || !in->Bool(&submap->finished) || !in->U8(&encoding)) {
    return false;
  }
  if (!(submap->limits.resolution_m > 0.0) || !std::isfinite(submap->limits.resolution_m) ||
      !std::isfinite(ox) || !std::isfinite(oy)) {
    in->Fail("submap grid resolution or origin is not a positive finite number");
    return false;
  }
  if (nx < 0 || ny < 0 || static_cast<uint64_t>(nx) * static_cast<uint64_t>(ny) > kMaxGridCells) {
    in->Fail("submap grid size " + std::to_string(nx) + " x " + std::to_string(ny) +
             " is out of range");
    return false;
  }
  if (num_range_data < 0) {
    in->Fail("negative num_range_data");
    return false;
  }
  if (encoding != kRawCells && encoding != kZlibCells) {
    in->Fail("unknown grid encoding " + std::to_string(encoding));
    return false;
  }
  if (!in->Bytes(&stored)) return false;
  const uint64_t num_cells = static_cast<uint64_t>(nx) * static_cast<uint64_t>(ny);
  const uint64_t raw_size = 2 * num_cells;
  std::string raw;
  if (encoding == kRawCells) {
    if (stored.size() != raw_size) {
      in->Fail("grid holds " + std::to_string(stored.size()) + " bytes, expected " +
               std::to_string(raw_size));
      return false;
    }
    raw.swap(stored);
  } else {
    if (raw_size > kMaxZlibRatio * stored.size() + 64) {
      in->Fail("compressed grid of " + std::to_string(stored.size()) + " bytes cannot hold " +
               std::to_string(raw_size));
      return false;
    }
    raw.resize(raw_size);
    uLongf size = raw_size;
    const int rc = uncompress(reinterpret_cast<Bytef*>(&raw[0]), &size,
                              reinterpret_cast<const Bytef*>(stored.data()), stored.size());
    if (rc != Z_OK || size != raw_size) {
      in->Fail("compressed grid does not inflate to " + std::to_string(raw_size) + " bytes");
      return false;
    }
  }
  submap->limits.origin_m = Eigen::Vector2d(ox, oy);
  submap->limits.num_x_cells = nx;
  submap->limits.num_y_cells = ny;
  submap->num_range_data = num_range_data;
  submap->cells.resize(num_cells);
  for (uint64_t i = 0; i < num_cells; ++i) {
    const uint16_t v = static_cast<uint16_t>(static_cast<uint8_t>(raw[2 * i]) |
                                             static_cast<uint8_t>(raw[2 * i + 1]) << 8);
    if (v > mapping::kMaxValue) {  // an update marker would break the grid's invariant
      in->Fail("grid cell " + std::to_string(i) + " holds invalid value " + std::to_string(v));
      return false;
    }
    submap->cells[i] = v;
  }
  return true;
}


}  // namespace io
}  // namespace fusemap
