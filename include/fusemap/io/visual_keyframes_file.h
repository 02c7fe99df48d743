#ifndef FUSEMAP_IO_VISUAL_KEYFRAMES_FILE_H_
#define FUSEMAP_IO_VISUAL_KEYFRAMES_FILE_H_

#include <string>
#include <vector>

#include "fusemap/common/rigid_transform.h"
#include "fusemap/visual_loop/visual_loop_checker.h"

namespace fusemap {
namespace io {

// What the visual loop checker's stage (session::VisualStage) needs to continue after a
// restart: its keyframes, where each one's base stood relative to its node, and the next
// keyframe id.
struct VisualKeyframesState {
  struct Entry {
    visual_loop::SavedKeyframe saved;
    common::Rigid2d T_node_base;
  };
  std::vector<Entry> keyframes;  // by increasing id
  int next_keyframe_id = 0;
};

// The compact binary (format 1; little-endian): magic "FMVKEYF\0", u32 format version,
// u64 payload length, u32 crc32 of the payload, then per keyframe id, node, submap, stamp,
// image size and intrinsics, T_base_camera, T_node_base, and per keypoint its position (f32),
// 32-byte descriptor, vocabulary node (u32) and 3D point (f32; NaN without depth), then the
// bag of words (word id u32, weight f32). No pixels.
std::string EncodeVisualKeyframes(const VisualKeyframesState& state);
// Refuses, with a reason naming `name`, a wrong magic or version, a truncated or corrupted
// file (checksum), and contents that break the invariants (ids not increasing or not below
// the next id, counts beyond what the file holds, non-finite poses).
bool DecodeVisualKeyframes(const std::string& bytes, const std::string& name,
                           VisualKeyframesState* state, std::string* error);

// Written atomically (see write_all.h).
bool WriteVisualKeyframesFile(const std::string& path, const VisualKeyframesState& state,
                              std::string* error);
// False with the reason if the file cannot be read or decoded.
bool ReadVisualKeyframesFile(const std::string& path, VisualKeyframesState* state,
                             std::string* error);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_VISUAL_KEYFRAMES_FILE_H_
