#ifndef FUSEMAP_SESSION_RUN_OUTPUTS_H_
#define FUSEMAP_SESSION_RUN_OUTPUTS_H_

#include <string>
#include <vector>

#include "fusemap/cloud/cloud_mapper.h"
#include "fusemap/eval/trajectory.h"
#include "fusemap/io/trajectory_archive.h"
#include "fusemap/pose_graph/map_builder_2d.h"
#include "fusemap/sensor/sensor_types.h"
#include "fusemap/visual_loop/loop_arbiter.h"

namespace fusemap {
namespace session {

// Time-ordered poses as a TUM trajectory, skipping repeated stamps (TUM needs increasing time).
eval::Trajectory ToTrajectory(const std::vector<pose_graph::MapBuilder2D::TimedPose2d>& poses);

// What a finished run (fusemap_offline, or fusemapd at shutdown) leaves behind.
struct RunOutputs {
  const pose_graph::MapBuilder2D* builder = nullptr;  // idle: after Finish()
  // In arrival order without samples that went back in time.
  const std::vector<sensor::OdometryData>* odometry = nullptr;
  // Where the odometry restarts (pose_graph::DensifyWithOdometry's breaks_s); a few stamps.
  std::vector<double> odometry_breaks_s;
  double map_resolution_m = 0.05;
  // Optional (null: no cloud outputs); after Finish(). Cloud files are written only if it
  // bound at least one frame.
  const cloud::CloudMapper* cloud_mapper = nullptr;
  // Optional (fusemapd): what the run moved out of memory; the trajectory files then cover the
  // archived nodes and odometry as well as the builder's nodes and `odometry`.
  const io::TrajectoryArchive* archive = nullptr;
  // Optional (with the visual loop checker): its decisions, written to DIR/loops.tsv.
  const std::vector<visual_loop::ArbitrationRecord>* loop_records = nullptr;
};

struct RunOutputsReport {
  std::vector<std::string> files;  // every file written, in order
  bool wrote_cloud = false;
  // "cloud_points=… cloud_frames_bound=… cloud_frames_dropped=… removed_dynamic=…
  // cloud_memory_mb=… cloud_points_per_m2=…" when wrote_cloud (no newline).
  std::string cloud_summary;
};

// Writes into `dir` (created if needed): DIR/trajectory.tum (a pose per odometry sample,
// pose_graph::DensifyWithOdometry), DIR/nodes.tum, DIR/odometry.tum (the odometry input),
// DIR/map.pgm + DIR/map.yaml (map_server), DIR/map.png (map with trajectory) and, with RGB-D
// frames bound, DIR/cloud.ply, DIR/cloud.pcd, DIR/cloud_removed.ply (points removed as
// dynamic), DIR/octomap.bt, DIR/octomap.ot and DIR/cloud.png (an oblique rendering); with
// loop_records, DIR/loops.tsv (io::WriteLoopsTsv).
bool WriteRunOutputs(const RunOutputs& run, const std::string& dir, RunOutputsReport* report,
                     std::string* error);

// The cloud summary line of a mapper (see RunOutputsReport::cloud_summary). Points per m² are
// over the floor area the map's points occupy in a grid of 0.5 m cells.
std::string CloudSummaryLine(const cloud::CloudMapper& mapper, const cloud::ColorCloud& map_cloud);

}  // namespace session
}  // namespace fusemap

#endif  // FUSEMAP_SESSION_RUN_OUTPUTS_H_
