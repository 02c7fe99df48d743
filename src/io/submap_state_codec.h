#ifndef FUSEMAP_IO_SUBMAP_STATE_CODEC_H_
#define FUSEMAP_IO_SUBMAP_STATE_CODEC_H_

#include "fusemap/common/rigid_transform.h"
#include "fusemap/mapping/submap_2d.h"
#include "byte_buffer.h"

namespace fusemap {
namespace io {

// x_m, y_m, angle_rad as three doubles; bit-exact round trip.
void EncodeRigid2d(const common::Rigid2d& T, ByteWriter* out);
bool DecodeRigid2d(ByteReader* in, common::Rigid2d* T);

// A stamp in seconds and a pose (EncodeRigid2d), as the checkpoint's odometry record and the
// trajectory archive store them. Decoding rejects a value that is not finite.
void EncodeTimedPose2d(double stamp_s, const common::Rigid2d& pose, ByteWriter* out);
bool DecodeTimedPose2d(ByteReader* in, double* stamp_s, common::Rigid2d* pose);

// A submap with its grid, which is the bulk of a checkpoint: cells as 16-bit little-endian
// values, raw or zlib-compressed (`compress`). Decoding checks the grid's size against the
// bytes present before allocating and rejects cell values a ProbabilityGrid cannot hold.
void EncodeSubmapState(const mapping::SubmapState2D& submap, bool compress, ByteWriter* out);
bool DecodeSubmapState(ByteReader* in, mapping::SubmapState2D* submap);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_SUBMAP_STATE_CODEC_H_
