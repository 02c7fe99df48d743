#ifndef FUSEMAP_DAEMON_RESUME_H_
#define FUSEMAP_DAEMON_RESUME_H_

#include <string>
#include <vector>

#include "fusemap/io/checkpoint.h"
#include "fusemap/pose_graph/map_builder_2d.h"
#include "fusemap/sensor/sensor_types.h"

namespace fusemap {
namespace daemon {

// What `fusemapd --resume` does before mapping. Policy (documented in fusemapd --help):
// - the newest valid checkpoint wins: `path`, or path.prev when `path` is missing, truncated or
//   fails its checksum (the reason is returned as a warning). The rejected file is then
//   renamed to path.rejected, so that the next save does not rotate it over the good .prev;
// - a checkpoint written by another fusemap version is refused (the state layout may differ);
// - a checkpoint mapped with a different configuration text is used with the current one and
//   a warning: submaps keep their own size and resolution, so tuning (or a changed daemon:
//   section) between runs is legitimate, but the caller should know.
struct ResumeCheckpoint {
  io::CheckpointContents contents;
  std::string used_path;
  std::vector<std::string> warnings;
};

enum class ResumeStatus { kOk, kUnreadable, kVersionMismatch };

ResumeStatus LoadResumeCheckpoint(const std::string& path, const std::string& options_yaml,
                                  ResumeCheckpoint* result, std::string* error);

// The last time in a restored state: its newest node's stamp, -infinity without nodes.
double LastStateStamp(const pose_graph::MapBuilderState2D& state);

}  // namespace daemon
}  // namespace fusemap

#endif  // FUSEMAP_DAEMON_RESUME_H_
