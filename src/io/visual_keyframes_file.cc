#include "fusemap/io/visual_keyframes_file.h"

#include <zlib.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "byte_buffer.h"
#include "submap_state_codec.h"
#include "write_all.h"

namespace fusemap {
namespace io {
namespace {

constexpr char kMagic[8] = {'F', 'M', 'V', 'K', 'E', 'Y', 'F', '\0'};
constexpr uint32_t kFormatVersion = 1;
constexpr size_t kHeaderBytes = 8 + 4 + 8 + 4;
constexpr int kDescriptorBytes = 32;

uint32_t Crc32(const std::string& bytes) {
  return static_cast<uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(bytes.size())));
}

void EncodeRigid3d(const common::Rigid3d& T, ByteWriter* out) {
  const Eigen::Vector3d t = T.translation();
  const Eigen::Quaterniond q = T.rotation();
  for (double v : {t.x(), t.y(), t.z(), q.w(), q.x(), q.y(), q.z()}) out->F64(v);
}

bool DecodeRigid3d(ByteReader* in, common::Rigid3d* T) {
  double v[7];
  for (double& x : v) {
    if (!in->F64(&x)) return false;
    if (!std::isfinite(x)) {
      in->Fail("non-finite camera mount");
      return false;
    }
  }
  const Eigen::Quaterniond q(v[3], v[4], v[5], v[6]);
  if (std::abs(q.norm() - 1.0) > 1e-6) {
    in->Fail("camera mount rotation is not a unit quaternion");
    return false;
  }
  *T = common::Rigid3d(Eigen::Vector3d(v[0], v[1], v[2]), q);
  return true;
}

void EncodeKeyframe(const VisualKeyframesState::Entry& entry, ByteWriter* out) {
  const visual_loop::Keyframe& k = entry.saved.keyframe;
  out->I32(k.id);
  out->I32(k.node);
  out->I32(k.submap);
  out->F64(k.stamp_s);
  out->I32(k.image_width);
  out->I32(k.image_height);
  out->I32(k.intrinsics.width);
  out->I32(k.intrinsics.height);
  for (double v : {k.intrinsics.fx, k.intrinsics.fy, k.intrinsics.cx, k.intrinsics.cy}) out->F64(v);
  EncodeRigid3d(entry.saved.T_base_camera, out);
  EncodeRigid2d(entry.T_node_base, out);
  out->U8(k.has_depth() ? 1 : 0);
  out->U8(k.vocabulary_nodes.empty() ? 0 : 1);
  out->U64(k.keypoints.size());
  for (size_t i = 0; i < k.keypoints.size(); ++i) {
    out->F32(k.keypoints[i].x);
    out->F32(k.keypoints[i].y);
    for (int b = 0; b < kDescriptorBytes; ++b) out->U8(k.descriptors.at<uint8_t>(static_cast<int>(i), b));
    if (!k.vocabulary_nodes.empty()) out->U32(k.vocabulary_nodes[i]);
    if (k.has_depth()) {
      for (int c = 0; c < 3; ++c) out->F32(k.points_camera[i][c]);
    }
  }
  out->U64(k.bow.size());
  for (const auto& [word, weight] : k.bow) {
    out->U32(word);
    out->F32(weight);
  }
}

bool DecodeKeyframe(ByteReader* in, VisualKeyframesState::Entry* entry) {
  visual_loop::Keyframe& k = entry->saved.keyframe;
  uint8_t has_depth = 0, has_nodes = 0;
  size_t n = 0;
  if (!in->I32(&k.id) || !in->I32(&k.node) || !in->I32(&k.submap) || !in->F64(&k.stamp_s) ||
      !in->I32(&k.image_width) || !in->I32(&k.image_height) || !in->I32(&k.intrinsics.width) ||
      !in->I32(&k.intrinsics.height) || !in->F64(&k.intrinsics.fx) || !in->F64(&k.intrinsics.fy) ||
      !in->F64(&k.intrinsics.cx) || !in->F64(&k.intrinsics.cy) ||
      !DecodeRigid3d(in, &entry->saved.T_base_camera) || !DecodeRigid2d(in, &entry->T_node_base) ||
      !in->U8(&has_depth) || !in->U8(&has_nodes) || !in->Count(8 + kDescriptorBytes, &n)) {
    return false;
  }
  if (has_depth > 1 || has_nodes > 1) {
    in->Fail("keyframe flags are not 0 or 1");
    return false;
  }
  k.keypoints.resize(n);
  k.descriptors = cv::Mat(static_cast<int>(n), kDescriptorBytes, CV_8UC1);
  if (has_nodes) k.vocabulary_nodes.resize(n);
  if (has_depth) k.points_camera.resize(n);
  for (size_t i = 0; i < n; ++i) {
    if (!in->F32(&k.keypoints[i].x) || !in->F32(&k.keypoints[i].y)) return false;
    const char* descriptor = in->Take(kDescriptorBytes);
    if (descriptor == nullptr) return false;
    std::memcpy(k.descriptors.ptr<uint8_t>(static_cast<int>(i)), descriptor, kDescriptorBytes);
    if (has_nodes && !in->U32(&k.vocabulary_nodes[i])) return false;
    if (has_depth) {
      for (int c = 0; c < 3; ++c) {
        if (!in->F32(&k.points_camera[i][c])) return false;
      }
    }
  }
  if (!in->Count(8, &n)) return false;
  k.bow.resize(n);
  for (auto& [word, weight] : k.bow) {
    if (!in->U32(&word) || !in->F32(&weight)) return false;
  }
  return true;
}

}  // namespace

std::string EncodeVisualKeyframes(const VisualKeyframesState& state) {
  std::string payload;
  ByteWriter out(&payload);
  out.I32(state.next_keyframe_id);
  out.U64(state.keyframes.size());
  for (const auto& entry : state.keyframes) EncodeKeyframe(entry, &out);
  std::string bytes(kMagic, sizeof(kMagic));
  ByteWriter header(&bytes);
  header.U32(kFormatVersion);
  header.U64(payload.size());
  header.U32(Crc32(payload));
  return bytes + payload;
}

bool DecodeVisualKeyframes(const std::string& bytes, const std::string& name,
                           VisualKeyframesState* state, std::string* error) {
  if (bytes.size() < kHeaderBytes || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0) {
    *error = name + ": not a visual keyframes file (bad magic or shorter than its header)";
    return false;
  }
  ByteReader header(bytes.data() + sizeof(kMagic), kHeaderBytes - sizeof(kMagic));
  uint32_t version = 0, crc = 0;
  uint64_t length = 0;
  header.U32(&version);
  header.U64(&length);
  header.U32(&crc);
  if (version != kFormatVersion) {
    *error = name + ": visual keyframes format version " + std::to_string(version) +
             ", this build reads version " + std::to_string(kFormatVersion);
    return false;
  }
  if (length != bytes.size() - kHeaderBytes) {
    *error = name + ": truncated (payload " + std::to_string(bytes.size() - kHeaderBytes) +
             " of " + std::to_string(length) + " bytes)";
    return false;
  }
  const std::string payload = bytes.substr(kHeaderBytes);
  if (Crc32(payload) != crc) {
    *error = name + ": checksum mismatch (corrupted)";
    return false;
  }
  ByteReader in(payload.data(), payload.size());
  VisualKeyframesState result;
  size_t n = 0;
  if (in.I32(&result.next_keyframe_id) && in.Count(100, &n)) {
    result.keyframes.resize(n);
    int previous = -1;
    for (auto& entry : result.keyframes) {
      if (!DecodeKeyframe(&in, &entry)) break;
      const int id = entry.saved.keyframe.id;
      if (id <= previous || id >= result.next_keyframe_id) {
        in.Fail("keyframe id " + std::to_string(id) + " is not increasing below the next id " +
                std::to_string(result.next_keyframe_id));
        break;
      }
      previous = id;
    }
  }
  if (in.ok() && in.remaining() != 0) in.Fail(std::to_string(in.remaining()) + " trailing bytes");
  if (!in.ok()) {
    *error = name + ": " + in.error();
    return false;
  }
  *state = std::move(result);
  return true;
}

bool WriteVisualKeyframesFile(const std::string& path, const VisualKeyframesState& state,
                              std::string* error) {
  return WriteFileAtomically(path, EncodeVisualKeyframes(state), error);
}

bool ReadVisualKeyframesFile(const std::string& path, VisualKeyframesState* state,
                             std::string* error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    *error = path + ": cannot read";
    return false;
  }
  std::stringstream bytes;
  bytes << in.rdbuf();
  return DecodeVisualKeyframes(bytes.str(), path, state, error);
}

}  // namespace io
}  // namespace fusemap
