#include "fusemap/daemon/resume.h"

#include <filesystem>
#include <limits>
#include <system_error>

#include "fusemap/eval/trajectory.h"
#include "fusemap/io/tum_trajectory.h"

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

std::vector<pose_graph::MapBuilder2D::TimedPose2d> ResumedTrajectory(
    const std::vector<pose_graph::MapBuilder2D::TimedPose2d>& nodes,
    const std::vector<sensor::OdometryData>& odometry) {
  if (odometry.empty()) return nodes;
  const double resume_s = odometry.front().stamp_s;
  std::vector<pose_graph::MapBuilder2D::TimedPose2d> before, after;
  for (const auto& node : nodes) (node.stamp_s < resume_s ? before : after).push_back(node);
  // Without a node of this run the increments have nothing to attach to.
  if (after.empty()) return nodes;
  auto trajectory = std::move(before);
  for (const auto& pose : pose_graph::DensifyWithOdometry(after, odometry)) {
    trajectory.push_back(pose);
  }
  return trajectory;
}

bool WriteResumedTrajectory(const pose_graph::MapBuilder2D& builder,
                            const std::vector<sensor::OdometryData>& odometry,
                            const std::string& dir, std::string* error) {
  eval::Trajectory trajectory;
  for (const auto& p : ResumedTrajectory(builder.NodePoses(), odometry)) {
    if (!trajectory.empty() && p.stamp_s <= trajectory.back().stamp_s) continue;
    trajectory.push_back({p.stamp_s, common::Rigid3d::FromRigid2d(p.pose)});
  }
  return io::WriteTumTrajectoryFile(dir + "/trajectory.tum", trajectory, error);
}

}  // namespace daemon
}  // namespace fusemap
