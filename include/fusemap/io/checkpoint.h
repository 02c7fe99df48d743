#ifndef FUSEMAP_IO_CHECKPOINT_H_
#define FUSEMAP_IO_CHECKPOINT_H_

#include <cstdint>
#include <string>

#include "fusemap/io/trajectory_archive.h"
#include "fusemap/pose_graph/map_builder_state_2d.h"
#include "fusemap/sensor/sensor_types.h"

namespace fusemap {
namespace io {

// Version string of this build, written into outputs and checkpoints.
const char* FusemapVersion();

// Checkpoint file layout (all integers little-endian):
//   header (36 bytes): magic "FUSEMAPCKPT\0", u32 format version, u32 flags (0),
//                      u64 payload length, u32 zlib crc32 of the payload,
//                      u32 crc32 of the preceding 32 header bytes
//   payload: fusemap version string, options YAML text, MapBuilderState2D
//            (see map_builder_state_codec.h; grids optionally zlib-compressed), the odometry
//            record, the trajectory archive's mark.
constexpr uint32_t kCheckpointFormatVersion = 9;

struct CheckpointContents {
  std::string fusemap_version = FusemapVersion();
  // The configuration the state was mapped with, verbatim, so a resume can compare or reuse it.
  std::string options_yaml;
  pose_graph::MapBuilderState2D state;
  // The odometry the run's trajectory output still needs (all of it without an archive).
  std::vector<sensor::OdometryData> odometry;
  // Where the run's TrajectoryArchive was (an empty mark when the run keeps none).
  TrajectoryArchiveMark archive;
};

// Replaces the checkpoint at `path` atomically: writes path.tmp and fsyncs it, renames the
// current file (if any) to path.prev, renames path.tmp to path, fsyncs the directory. A crash
// at any point leaves a complete checkpoint at path or at path.prev. Exactly one previous
// checkpoint is kept.
bool WriteCheckpoint(const std::string& path, const CheckpointContents& contents,
                     std::string* error, bool compress_grids = true);

// Reads and fully validates a checkpoint: bad magic, other format version, truncation,
// checksum mismatch, absurd sizes and inconsistent state are errors naming the file.
bool ReadCheckpoint(const std::string& path, CheckpointContents* contents, std::string* error);

// Reads `path`, or if it is missing or corrupt, path.prev. On success *used_path says which;
// *error is then empty, or (after falling back) says why `path` was rejected, for the caller
// to report. On failure *error gives the problems with both files.
bool ReadLatestCheckpoint(const std::string& path, CheckpointContents* contents,
                          std::string* used_path, std::string* error);

// The file image without the file (tests, sending over a network). `name` is used in errors.
std::string EncodeCheckpoint(const CheckpointContents& contents, bool compress_grids);
bool DecodeCheckpoint(const std::string& bytes, const std::string& name,
                      CheckpointContents* contents, std::string* error);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_CHECKPOINT_H_
