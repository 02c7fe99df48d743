#include "fusemap/daemon/resume.h"

#include <filesystem>
#include <limits>
#include <system_error>


namespace fusemap {
namespace daemon {

ResumeStatus LoadResumeCheckpoint(const std::string& path, const std::string& options_yaml,
                                  ResumeCheckpoint* result, std::string* error) {
  std::string why;
  if (!io::ReadLatestCheckpoint(path, &result->contents, &result->used_path, &why)) {
    *error = "no usable checkpoint: " + why;
    return ResumeStatus::kUnreadable;
  }
  if (!why.empty()) {
    result->warnings.push_back("using the previous checkpoint " + result->used_path + ": " + why);
    // The next save would rotate the rejected file over the good .prev: set it aside.
    std::error_code ec;
    if (std::filesystem::exists(path, ec)) {
      std::filesystem::rename(path, path + ".rejected", ec);
      result->warnings.push_back(ec ? "cannot rename " + path + ": " + ec.message()
                                    : "kept the rejected file as " + path + ".rejected");
    }
  }
  if (result->contents.fusemap_version != io::FusemapVersion()) {
    *error = result->used_path + " was written by fusemap " + result->contents.fusemap_version +
             ", this is " + io::FusemapVersion() +
             "; its state cannot be restored (start without --resume, or use that version)";
    return ResumeStatus::kVersionMismatch;
  }
  if (result->contents.options_yaml != options_yaml) {
    result->warnings.push_back(result->used_path +
                               " was mapped with a different configuration; continuing with the "
                               "current one");
  }
  return ResumeStatus::kOk;
}

double LastStateStamp(const pose_graph::MapBuilderState2D& state) {
  if (state.pose_graph.nodes.empty()) return -std::numeric_limits<double>::infinity();
  return state.pose_graph.nodes.back().stamp_s;
}

}  // namespace daemon
}  // namespace fusemap
