#include "fusemap/daemon/map_outputs.h"

#include <filesystem>
#include <system_error>

#include "fusemap/io/map_writer.h"
#include "fusemap/io/tum_trajectory.h"
#include "fusemap/mapping/grid_image.h"

namespace fusemap {
namespace daemon {

eval::Trajectory ToTrajectory(const std::vector<pose_graph::MapBuilder2D::TimedPose2d>& poses) {
  eval::Trajectory trajectory;
  for (const auto& p : poses) {
    if (!trajectory.empty() && p.stamp_s <= trajectory.back().stamp_s) continue;
    trajectory.push_back({p.stamp_s, common::Rigid3d::FromRigid2d(p.pose)});
  }
  return trajectory;
}

bool WriteMapOutputs(const pose_graph::MapBuilder2D& builder,
                     const std::vector<sensor::OdometryData>& odometry, double resolution_m,
                     const std::string& dir, std::string* error) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    *error = "cannot create output folder " + dir + ": " + ec.message();
    return false;
  }
  const auto nodes = builder.NodePoses();
  const auto dense = pose_graph::DensifyWithOdometry(nodes, odometry);
  const std::string out = dir + "/";
  if (!io::WriteTumTrajectoryFile(out + "trajectory.tum", ToTrajectory(dense), error) ||
      !io::WriteTumTrajectoryFile(out + "nodes.tum", ToTrajectory(nodes), error)) {
    return false;
  }
  const auto snapshot = builder.pose_graph().Snapshot();
  const auto submaps = builder.pose_graph().submaps();
  std::vector<mapping::PlacedGrid> grids;
  for (size_t i = 0; i < submaps.size() && i < snapshot->T_map_submaps.size(); ++i) {
    grids.emplace_back(snapshot->T_map_submaps[i] * submaps[i]->T_local_submap().inverse(),
                       &submaps[i]->grid());
  }
  if (grids.empty()) {
    *error = "no submaps yet: no map written";
    return false;
  }
  const mapping::GridImage image = mapping::RenderMap(grids, resolution_m);
  io::MapImage map;
  map.width = image.width;
  map.height = image.height;
  map.resolution_m = image.resolution_m;
  map.origin_m = image.origin_m;
  map.pixels = image.pixels;
  std::vector<Eigen::Vector2d> xy;
  for (const auto& p : dense) xy.push_back(p.pose.translation());
  return io::WriteMapPgmYaml(map, out + "map", error) &&
         io::WriteMapPng(map, xy, out + "map.png", error);
}

}  // namespace daemon
}  // namespace fusemap
