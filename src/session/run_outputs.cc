#include "fusemap/session/run_outputs.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>
#include <unordered_set>
#include <utility>

#include "fusemap/io/cloud_image.h"
#include "fusemap/io/cloud_writer.h"
#include "fusemap/io/loop_tables_file.h"
#include "fusemap/io/loops_file.h"
#include "fusemap/io/map_writer.h"
#include "fusemap/io/tum_trajectory.h"
#include "fusemap/mapping/grid_image.h"

namespace fusemap {
namespace session {
namespace {

// Surface area is estimated by counting occupied cells of this edge: a surface crossing a cell
// covers about one cell face of it.
constexpr double kAreaCellM = 0.1;

bool WriteMap(const RunOutputs& run, const std::vector<Eigen::Vector2d>& xy,
              const std::string& out, RunOutputsReport* report, mapping::GridImage* image_out,
              std::string* error) {
  const auto snapshot = run.builder->pose_graph().Snapshot();
  const auto submaps = run.builder->pose_graph().submaps();
  // Compacted submaps are inflated one at a time while drawn.
  std::vector<mapping::GridSource> grids;
  for (size_t i = 0; i < submaps.size() && i < snapshot->T_map_submaps.size(); ++i) {
    if (!submaps[i]) continue;  // trimmed: newer submaps cover its area
    grids.push_back({snapshot->T_map_submaps[i] * submaps[i]->T_local_submap().inverse(),
                     [submap = submaps[i]] { return submap->grid(); }});
  }
  if (grids.empty()) {
    *error = "no submaps yet: no map written";
    return false;
  }
  *image_out = mapping::RenderMap(grids, run.map_resolution_m);
  // The pixels are lent to the writers, not copied: a campus-sized map has tens of millions,
  // and map.png's colour canvas already takes three bytes for each.
  io::MapImage map;
  map.width = image_out->width;
  map.height = image_out->height;
  map.resolution_m = image_out->resolution_m;
  map.origin_m = image_out->origin_m;
  map.pixels = std::move(image_out->pixels);
  const bool written = io::WriteMapPgmYaml(map, out + "map", error) &&
                       io::WriteMapPng(map, xy, out + "map.png", error);
  image_out->pixels = std::move(map.pixels);
  if (!written) return false;
  report->files.insert(report->files.end(), {out + "map.pgm", out + "map.yaml", out + "map.png"});
  return true;
}

// True where the laser map is free at (x, y) and within margin_m around it.
bool FreeInLaserMap(const mapping::GridImage& map, double margin_m, double x_m, double y_m) {
  const int col = static_cast<int>(std::floor((x_m - map.origin_m.x()) / map.resolution_m));
  const int row = map.height - 1 -
                  static_cast<int>(std::floor((y_m - map.origin_m.y()) / map.resolution_m));
  const int r = static_cast<int>(std::ceil(margin_m / map.resolution_m));
  if (col - r < 0 || row - r < 0 || col + r >= map.width || row + r >= map.height) return false;
  for (int dr = -r; dr <= r; ++dr) {
    for (int dc = -r; dc <= r; ++dc) {
      if (map.at(row + dr, col + dc) != mapping::kFreePixel) return false;
    }
  }
  return true;
}

bool WriteCloud(const cloud::CloudMapper& mapper, const mapping::GridImage& laser_map,
                const std::string& out, RunOutputsReport* report, std::string* error) {
  std::vector<uint16_t> hits;
  const cloud::ColorCloud::Ptr map_cloud = mapper.binder().GlobalCloud(&hits);
  cloud::ColorCloud removed_points = mapper.binder().removed_points();
  const cloud::FreeColumnFilterOptions& free_space = mapper.options().laser_free_space;
  const size_t removed_free = cloud::RemoveInFreeColumns(
      [&](double x_m, double y_m) {
        return FreeInLaserMap(laser_map, free_space.margin_m, x_m, y_m);
      },
      free_space, hits, map_cloud.get(), &removed_points);
  const std::string ply = out + "cloud.ply", pcd = out + "cloud.pcd";
  const std::string removed = out + "cloud_removed.ply";
  const std::string bt = out + "octomap.bt", ot = out + "octomap.ot", png = out + "cloud.png";
  if (!io::WriteCloudPly(ply, *map_cloud, error) || !io::WriteCloudPcd(pcd, *map_cloud, error) ||
      !io::WriteCloudPly(removed, removed_points, error) ||
      !io::WriteOctoMaps(*map_cloud, mapper.options().octomap_resolution_m, bt, ot, error)) {
    return false;
  }
  report->files.insert(report->files.end(), {ply, pcd, removed, bt, ot});
  if (!map_cloud->empty()) {
    if (!io::WriteCloudPng(*map_cloud, io::CloudImageOptions(), png, error)) return false;
    report->files.push_back(png);
  }
  report->wrote_cloud = true;
  report->cloud_summary = CloudSummaryLine(mapper, *map_cloud) +
                          " removed_laser_free=" + std::to_string(removed_free);
  return true;
}

}  // namespace

namespace {

// DIR/submaps.tsv (each held submap's map pose and the first node inserted into it, which ties
// the submap frame to a true pose for fusemap_eval loops) and, when no visual stage records the
// loop decisions (graph_loops), DIR/loops.tsv: the graph's laser loop closures as they stand at
// the end, all `laser_kept`.
bool WriteLoopTables(const pose_graph::PoseGraph2D& graph, bool graph_loops, const std::string& out,
                     RunOutputsReport* report, std::string* error) {
  std::vector<std::shared_ptr<const mapping::Submap2D>> submaps;
  const pose_graph::PoseGraphState2D state = graph.ExportState(&submaps);
  std::vector<int> first_node(state.T_map_submaps.size(), -1);
  for (const auto& node : state.nodes) {
    for (int submap : node.inserted_into) {
      if (submap >= 0 && submap < static_cast<int>(first_node.size()) && first_node[submap] < 0) {
        first_node[submap] = node.index;
      }
    }
  }
  std::vector<eval::SubmapAnchor> anchors;
  for (size_t i = 0; i < first_node.size(); ++i) {
    if (first_node[i] >= 0) anchors.push_back({static_cast<int>(i), first_node[i], state.T_map_submaps[i]});
  }
  if (!io::WriteSubmapAnchorsFile(out + "submaps.tsv", anchors, error)) return false;
  report->files.push_back(out + "submaps.tsv");
  if (!graph_loops) return true;
  std::vector<visual_loop::ArbitrationRecord> loops;
  for (const pose_graph::Constraint2D& c : state.constraints) {
    if (c.tag != pose_graph::Constraint2D::kInterSubmap) continue;
    visual_loop::ArbitrationRecord record;
    record.node = c.node;
    record.submap = c.submap;
    record.laser = visual_loop::LoopMeasurement2D{c.T_submap_node};
    record.laser->laser_score = c.laser_score;
    record.laser->unmeasured_direction = c.unmeasured_direction;
    record.laser->unmeasured_turn_rad_per_m = c.unmeasured_turn_rad_per_m;
    loops.push_back(record);
  }
  if (!io::WriteLoopsTsv(out + "loops.tsv", loops, error)) return false;
  report->files.push_back(out + "loops.tsv");
  return true;
}

}  // namespace

eval::Trajectory ToTrajectory(const std::vector<pose_graph::MapBuilder2D::TimedPose2d>& poses) {
  eval::Trajectory trajectory;
  for (const auto& p : poses) {
    if (!trajectory.empty() && p.stamp_s <= trajectory.back().stamp_s) continue;
    trajectory.push_back({p.stamp_s, common::Rigid3d::FromRigid2d(p.pose)});
  }
  return trajectory;
}

std::string CloudSummaryLine(const cloud::CloudMapper& mapper, const cloud::ColorCloud& map_cloud) {
  std::unordered_set<int64_t> cells;
  for (const cloud::ColorPoint& p : map_cloud) {
    const auto cell = [](float v) { return static_cast<int64_t>(std::floor(v / kAreaCellM)); };
    // 21 bits per axis: +-100 km at 0.1 m.
    cells.insert(((cell(p.x) & 0x1fffff) << 42) | ((cell(p.y) & 0x1fffff) << 21) |
                 (cell(p.z) & 0x1fffff));
  }
  const double area_m2 = static_cast<double>(cells.size()) * kAreaCellM * kAreaCellM;
  const cloud::CloudMapperStats& s = mapper.stats();
  const int64_t dropped = s.frames_dropped_no_pose + s.frames_dropped_queue +
                          s.frames_dropped_no_submap;
  const double voxel_m = mapper.binder().options().voxel_size_m;
  char line[320];
  std::snprintf(line, sizeof(line),
                "cloud_points=%zu cloud_frames_in=%lld cloud_frames_bound=%lld "
                "cloud_frames_skipped_rate=%lld cloud_frames_dropped=%lld removed_dynamic=%lld "
                "cloud_memory_mb=%.1f cloud_points_per_m2=%.0f cloud_points_per_m2_bound=%.0f",
                map_cloud.size(), static_cast<long long>(s.frames_in),
                static_cast<long long>(s.frames_bound),
                static_cast<long long>(s.frames_skipped_rate), static_cast<long long>(dropped),
                static_cast<long long>(mapper.binder().stats().points_removed_dynamic),
                mapper.binder().MemoryBytes() / (1024.0 * 1024.0),
                area_m2 > 0.0 ? static_cast<double>(map_cloud.size()) / area_m2 : 0.0,
                1.0 / (voxel_m * voxel_m));
  return line;
}

bool WriteRunOutputs(const RunOutputs& run, const std::string& dir, RunOutputsReport* report,
                     std::string* error) {
  *report = RunOutputsReport();
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    *error = "cannot create output folder " + dir + ": " + ec.message();
    return false;
  }
  auto nodes = run.builder->NodePoses();
  std::vector<sensor::OdometryData> archived_odometry;
  if (run.archive != nullptr) {
    std::vector<pose_graph::MapBuilder2D::TimedPose2d> held = std::move(nodes);
    if (!run.archive->ReadWholeRun(held, *run.odometry, &nodes, &archived_odometry, error)) {
      return false;
    }
  }
  const std::vector<sensor::OdometryData>& odometry =
      run.archive != nullptr ? archived_odometry : *run.odometry;
  const auto dense = pose_graph::DensifyWithOdometry(nodes, odometry, run.odometry_breaks_s);
  std::vector<pose_graph::MapBuilder2D::TimedPose2d> raw_odometry;
  for (const auto& o : odometry) raw_odometry.push_back({o.stamp_s, o.pose});
  const std::string out = dir + "/";
  if (!io::WriteTumTrajectoryFile(out + "trajectory.tum", ToTrajectory(dense), error) ||
      !io::WriteTumTrajectoryFile(out + "nodes.tum", ToTrajectory(nodes), error) ||
      !io::WriteTumTrajectoryFile(out + "odometry.tum", ToTrajectory(raw_odometry), error)) {
    return false;
  }
  report->files.insert(report->files.end(),
                       {out + "trajectory.tum", out + "nodes.tum", out + "odometry.tum"});
  if (!WriteLoopTables(run.builder->pose_graph(), run.loop_records == nullptr, out, report, error)) {
    return false;
  }
  std::vector<Eigen::Vector2d> xy;
  for (const auto& p : dense) xy.push_back(p.pose.translation());
  if (run.loop_records != nullptr) {
    if (!io::WriteLoopsTsv(out + "loops.tsv", *run.loop_records, error)) return false;
    report->files.push_back(out + "loops.tsv");
  }
  mapping::GridImage laser_map;
  if (!WriteMap(run, xy, out, report, &laser_map, error)) return false;
  if (run.cloud_mapper != nullptr && run.cloud_mapper->stats().frames_bound > 0) {
    return WriteCloud(*run.cloud_mapper, laser_map, out, report, error);
  }
  return true;
}

}  // namespace session
}  // namespace fusemap
