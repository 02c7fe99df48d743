#include "fusemap/daemon/file_checkpointer.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <system_error>
#include <utility>

#include "fusemap/io/checkpoint.h"

namespace fusemap {
namespace daemon {

std::string CheckpointPath(const std::string& out_dir) { return out_dir + "/checkpoint.fmck"; }

FileCheckpointer::FileCheckpointer(std::string path, std::string options_yaml, LogLine log)
    : path_(std::move(path)), options_yaml_(std::move(options_yaml)), log_(std::move(log)) {}

bool FileCheckpointer::Save(pose_graph::MapBuilder2D& builder, const RunRecord& record,
                            std::string* error) {
  const auto start = std::chrono::steady_clock::now();
  io::CheckpointContents contents;
  contents.options_yaml = options_yaml_;
  contents.state = builder.ExportState();
  if (record.odometry != nullptr) contents.odometry = *record.odometry;
  if (record.archive != nullptr) contents.archive = *record.archive;
  const int nodes = static_cast<int>(contents.state.pose_graph.nodes.size());
  std::error_code ec;
  const auto parent = std::filesystem::path(path_).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
  const bool ok = io::WriteCheckpoint(path_, contents, error);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto bytes = ok ? std::filesystem::file_size(path_, ec) : 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (ok) {
      ++stats_.saved;
      stats_.last_bytes = ec ? 0 : static_cast<int64_t>(bytes);
      stats_.last_seconds = seconds;
      stats_.last_nodes = nodes;
    } else {
      ++stats_.failed;
    }
  }
  if (ok && log_) {
    char line[256];
    std::snprintf(line, sizeof(line), "checkpoint %s: %d nodes, %.2f MB in %.3f s", path_.c_str(),
                  nodes, static_cast<double>(bytes) / 1048576.0, seconds);
    log_(line);
  }
  return ok;
}

FileCheckpointer::Stats FileCheckpointer::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stats_;
}

}  // namespace daemon
}  // namespace fusemap
