#include "fusemap/pose_graph/map_builder_2d.h"

#include <algorithm>
#include <cassert>
#include <utility>

namespace fusemap {
namespace pose_graph {

MapBuilderOptions2D ParseMapBuilderOptions2D(common::ConfigReader& reader) {
  MapBuilderOptions2D options;
  options.local_slam = mapping::ParseLocalTrajectoryBuilderOptions2D(reader.Child("local_slam"));
  options.global_slam = ParsePoseGraphOptions2D(reader.Child("global_slam"));
  return options;
}

MapBuilder2D::MapBuilder2D(const MapBuilderOptions2D& options, common::Executor* executor)
    : local_(options.local_slam), pose_graph_(options.global_slam, executor) {}

std::optional<MapBuilder2D::ScanResult> MapBuilder2D::AddScan(const sensor::LaserScan& scan) {
  auto result = local_.AddScan(scan);
  if (!result) return std::nullopt;
  if (result->insertion) {
    newest_node_ = pose_graph_.AddNode(result->stamp_s, result->T_local_tracking,
                        result->insertion->filtered_cloud, result->insertion->insertion_submaps);
  }
  ScanResult out;
  out.node = newest_node_;
  out.T_local_tracking = result->T_local_tracking;
  out.T_map_tracking = pose_graph_.T_map_local() * result->T_local_tracking;
  const auto active = local_.active_submaps();
  if (!active.empty()) {
    out.submap_id = pose_graph_.SubmapIndex(active.front().get());
    out.T_local_submap = active.front()->T_local_submap();
  }
  return out;
}

MapBuilderState2D MapBuilder2D::ExportState() const {
  MapBuilderState2D state;
  std::vector<std::shared_ptr<const mapping::Submap2D>> submaps;
  state.pose_graph = pose_graph_.ExportState(&submaps);
  state.local_slam = local_.ExportState();
  // Grids are copied outside the pose graph's lock: finished submaps are immutable and the
  // unfinished ones are only written by AddScan, on this thread.
  state.submaps.reserve(submaps.size());
  // A trimmed submap keeps its index, finished and with an empty grid.
  mapping::SubmapState2D trimmed;
  trimmed.finished = true;
  for (const auto& submap : submaps) {
    state.submaps.push_back(submap ? submap->ExportState() : trimmed);
  }
  for (const auto& active : local_.active_submaps()) {
    const auto it = std::find(submaps.begin(), submaps.end(), active);
    // Every submap local SLAM starts reaches the pose graph with the scan that started it.
    assert(it != submaps.end());
    state.active_submaps.push_back(static_cast<int>(it - submaps.begin()));
  }
  return state;
}

std::unique_ptr<MapBuilder2D> MapBuilder2D::Restore(const MapBuilderOptions2D& options,
                                                    common::Executor* executor,
                                                    const MapBuilderState2D& state) {
  auto builder = std::make_unique<MapBuilder2D>(options, executor);
  std::vector<std::shared_ptr<mapping::Submap2D>> submaps;
  submaps.reserve(state.submaps.size());
  for (size_t s = 0; s < state.submaps.size(); ++s) {
    submaps.push_back(state.pose_graph.submaps[s].trimmed
                          ? nullptr
                          : std::make_shared<mapping::Submap2D>(state.submaps[s]));
  }
  std::vector<std::shared_ptr<mapping::Submap2D>> active;
  for (int index : state.active_submaps) active.push_back(submaps.at(index));
  // As AddNode does once local SLAM lets go of a finished submap.
  for (const auto& submap : submaps) {
    if (submap && submap->finished() &&
        std::find(active.begin(), active.end(), submap) == active.end()) {
      submap->Compact();
    }
  }
  builder->local_.RestoreState(state.local_slam, std::move(active));
  builder->pose_graph_.RestoreState(
      state.pose_graph,
      std::vector<std::shared_ptr<const mapping::Submap2D>>(submaps.begin(), submaps.end()));
  builder->newest_node_ = state.pose_graph.stats.nodes - 1;
  return builder;
}

std::vector<MapBuilder2D::TimedPose2d> MapBuilder2D::NodePoses() const {
  const auto snapshot = pose_graph_.Snapshot();
  const std::vector<double> stamps = pose_graph_.node_stamps_s();
  std::vector<TimedPose2d> poses;
  const size_t n = std::min(stamps.size(), snapshot->T_map_nodes.size());
  for (size_t i = 0; i < n; ++i) poses.push_back({stamps[i], snapshot->T_map_nodes[i]});
  return poses;
}

namespace {

// Odometry pose at `stamp_s` by interpolation between the neighbouring samples.
common::Rigid2d OdometryAt(const std::vector<sensor::OdometryData>& odometry, double stamp_s) {
  const auto it = std::lower_bound(
      odometry.begin(), odometry.end(), stamp_s,
      [](const sensor::OdometryData& o, double t) { return o.stamp_s < t; });
  if (it == odometry.begin()) return it->pose;
  if (it == odometry.end()) return odometry.back().pose;
  const auto& b = *it;
  const auto& a = *(it - 1);
  const double span = b.stamp_s - a.stamp_s;
  return common::Interpolate(a.pose, b.pose, span > 0 ? (stamp_s - a.stamp_s) / span : 1.0);
}

}  // namespace

std::vector<MapBuilder2D::TimedPose2d> DensifyWithOdometry(
    const std::vector<MapBuilder2D::TimedPose2d>& nodes,
    const std::vector<sensor::OdometryData>& odometry, const std::vector<double>& breaks_s) {
  if (odometry.empty() || nodes.empty()) return nodes;
  // Each node's pose as predicted from its odometry: T_map_node * T_odom_node^-1 maps odometry
  // poses into the map frame as that node sees them.
  std::vector<common::Rigid2d> T_map_odom;
  T_map_odom.reserve(nodes.size());
  for (const auto& node : nodes) {
    T_map_odom.push_back(node.pose * OdometryAt(odometry, node.stamp_s).inverse());
  }
  std::vector<MapBuilder2D::TimedPose2d> dense;
  dense.reserve(odometry.size());
  size_t next = 0;  // first node after the sample
  for (const auto& sample : odometry) {
    // Repeated odometry stamps would give a trajectory with two poses at one time.
    if (!dense.empty() && sample.stamp_s <= dense.back().stamp_s) continue;
    while (next < nodes.size() && nodes[next].stamp_s <= sample.stamp_s) ++next;
    common::Rigid2d pose;
    if (next == 0 || next == nodes.size()) {
      pose = T_map_odom[next == 0 ? 0 : next - 1] * sample.pose;
    } else {
      // Between two nodes the odometry drift accumulated from one to the other is spread over
      // the interval: blend the two nodes' predictions by time fraction.
      const auto& a = nodes[next - 1];
      const auto& b = nodes[next];
      const auto reset = std::find_if(breaks_s.begin(), breaks_s.end(), [&](double t) {
        return t > a.stamp_s && t <= b.stamp_s;
      });
      if (reset != breaks_s.end()) {
        pose = sample.stamp_s < *reset ? T_map_odom[next - 1] * sample.pose
                                       : T_map_odom[next] * sample.pose;
      } else {
        const double span = b.stamp_s - a.stamp_s;
        const double fraction = span > 0 ? (sample.stamp_s - a.stamp_s) / span : 0.0;
        pose = common::Interpolate(T_map_odom[next - 1] * sample.pose,
                                   T_map_odom[next] * sample.pose, fraction);
      }
    }
    dense.push_back({sample.stamp_s, pose});
  }
  return dense;
}

}  // namespace pose_graph
}  // namespace fusemap
