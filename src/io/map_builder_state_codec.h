#ifndef FUSEMAP_IO_MAP_BUILDER_STATE_CODEC_H_
#define FUSEMAP_IO_MAP_BUILDER_STATE_CODEC_H_

#include "fusemap/pose_graph/map_builder_state_2d.h"
#include "byte_buffer.h"

namespace fusemap {
namespace io {

// Writes `state` in the checkpoint's binary layout: fixed-width little-endian fields, counts
// before lists, grids either raw or zlib-compressed (each grid says which).
void EncodeMapBuilderState(const pose_graph::MapBuilderState2D& state, bool compress_grids,
                           ByteWriter* out);

// Reads what EncodeMapBuilderState wrote and checks MapBuilderState2D's invariants, so that
// MapBuilder2D::Restore can trust the result. On failure returns false with the reason in
// in->error(); never allocates more than the input could describe.
bool DecodeMapBuilderState(ByteReader* in, pose_graph::MapBuilderState2D* state);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_MAP_BUILDER_STATE_CODEC_H_
