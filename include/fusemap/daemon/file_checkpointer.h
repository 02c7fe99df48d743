#ifndef FUSEMAP_DAEMON_FILE_CHECKPOINTER_H_
#define FUSEMAP_DAEMON_FILE_CHECKPOINTER_H_

#include <cstdint>
#include <functional>
#include <mutex>
#include <string>

#include "fusemap/daemon/publisher.h"

namespace fusemap {
namespace daemon {

// Where fusemapd keeps its checkpoint in the output folder: DIR/checkpoint.fmck, and the one
// before it as DIR/checkpoint.fmck.prev (io::WriteCheckpoint's rotation).
std::string CheckpointPath(const std::string& out_dir);

// The engine's Checkpointer: the builder's state, the configuration text and the version,
// written atomically by io::WriteCheckpoint. Each save is logged with its size and duration.
// Save runs on the SLAM thread; stats() may be read from any thread.
class FileCheckpointer : public Checkpointer {
 public:
  using LogLine = std::function<void(const std::string&)>;

  // `options_yaml`: the configuration file's text, stored verbatim for --resume to compare.
  FileCheckpointer(std::string path, std::string options_yaml, LogLine log = nullptr);

  bool Save(pose_graph::MapBuilder2D& builder, const RunRecord& record,
            std::string* error) override;

  struct Stats {
    int saved = 0;
    int failed = 0;
    int64_t last_bytes = 0;
    double last_seconds = 0.0;  // export + encode + write + fsync
    int last_nodes = 0;
  };
  Stats stats() const;
  const std::string& path() const { return path_; }

 private:
  const std::string path_;
  const std::string options_yaml_;
  const LogLine log_;
  mutable std::mutex mutex_;
  Stats stats_;  // guarded by mutex_
};

}  // namespace daemon
}  // namespace fusemap

#endif  // FUSEMAP_DAEMON_FILE_CHECKPOINTER_H_
