#include "fusemap/io/reference_map.h"

#include <memory>

#include "fusemap/io/lcm_conversions.h"
#include "fusemap/io/lcm_log.h"
#include "fusemap/mapping/grid_image.h"
#include "fusemap/mapping/probability_grid.h"
#include "fusemap/mapping/range_data_inserter_2d.h"
#include "fusemap/sensor/range_data_builder.h"
#include "fusemap/sensor/voxel_filter.h"

namespace fusemap {
namespace io {
namespace {

// Scan stamps and reference stamps are the same numbers written by one program.
constexpr double kMaxStampDiffS = 1e-3;

}  // namespace

bool RenderLogAtPoses(const std::string& log_path, const SlamConfig& config,
                      const eval::Trajectory& poses, const common::Rigid2d& T_out_map,
                      ReferenceMap* out, std::string* error) {
  *out = ReferenceMap();
  LcmLogReader reader;
  if (!reader.Open(log_path, error)) return false;
  const mapping::LocalTrajectoryBuilderOptions2D& local = config.map_builder.local_slam;
  const mapping::RangeDataInserter2D inserter(local.submaps.range_data_inserter);
  std::vector<std::unique_ptr<mapping::ProbabilityGrid>> grids;
  LogEvent event;
  while (reader.Next(&event)) {
    if (event.channel != config.channels.lidar) continue;
    sensor::LaserScan scan;
    std::string reason;
    if (!DecodeLaserScan(event.data.data(), static_cast<int>(event.data.size()), config.lidar,
                         &scan, &reason)) {
      *error = log_path + ": message " + std::to_string(out->scans_read + 1) + " on " +
               event.channel + ": " + reason;
      return false;
    }
    ++out->scans_read;
    common::Rigid3d T_map_tracking;
    if (!eval::LookUpPose(poses, scan.stamp_s, kMaxStampDiffS, &T_map_tracking)) continue;
    const common::Rigid2d T_out_tracking = T_out_map * T_map_tracking.ToRigid2d();
    // As local SLAM inserts a scan (range gate, mounting, voxel filter), at the given pose.
    const sensor::RangeData in_tracking = sensor::VoxelFilter(
        sensor::TransformRangeData(sensor::RangeDataFromScan(scan, local.range_gate),
                                   local.T_tracking_laser),
        local.voxel_filter_size_m);
    // As local SLAM's two active submaps: a new grid every num_range_data scans, each scan
    // into the newest two.
    if (out->scans_used % local.submaps.num_range_data == 0) {
      const double resolution_m = local.submaps.resolution_m;
      // As a new submap: 100 x 100 cells centred on the pose; the grid grows as needed.
      const Eigen::Vector2d corner_m =
          T_out_tracking.translation() - Eigen::Vector2d::Constant(50.0 * resolution_m);
      grids.push_back(std::make_unique<mapping::ProbabilityGrid>(
          mapping::MapLimits{resolution_m, corner_m, 100, 100}));
    }
    const sensor::RangeData in_out = sensor::TransformRangeData(in_tracking, T_out_tracking);
    for (size_t i = grids.size() >= 2 ? grids.size() - 2 : 0; i < grids.size(); ++i) {
      inserter.Insert(in_out, grids[i].get());
    }
    out->trajectory_xy.push_back(T_out_tracking.translation());
    ++out->scans_used;
  }
  if (grids.empty()) {
    *error = log_path + ": no scan on channel " + config.channels.lidar +
             " has a pose within 1 ms of its stamp (" + std::to_string(out->scans_read) +
             " scans, " + std::to_string(poses.size()) + " poses)";
    return false;
  }
  std::vector<mapping::PlacedGrid> placed;
  for (const auto& grid : grids) placed.emplace_back(common::Rigid2d::Identity(), grid.get());
  const mapping::GridImage image = mapping::RenderMap(placed, local.submaps.resolution_m);
  out->map.width = image.width;
  out->map.height = image.height;
  out->map.resolution_m = image.resolution_m;
  out->map.origin_m = image.origin_m;
  out->map.pixels = image.pixels;
  return true;
}

bool AnchorOnFirstPose(const eval::Trajectory& poses, const eval::Trajectory& anchor,
                       common::Rigid2d* T_anchor_poses) {
  common::Rigid3d T_poses_first;
  if (anchor.empty() ||
      !eval::LookUpPose(poses, anchor.front().stamp_s, kMaxStampDiffS, &T_poses_first)) {
    return false;
  }
  *T_anchor_poses = anchor.front().pose.ToRigid2d() * T_poses_first.ToRigid2d().inverse();
  return true;
}

}  // namespace io
}  // namespace fusemap
