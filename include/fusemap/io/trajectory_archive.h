#ifndef FUSEMAP_IO_TRAJECTORY_ARCHIVE_H_
#define FUSEMAP_IO_TRAJECTORY_ARCHIVE_H_

#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "fusemap/eval/trajectory.h"
#include "fusemap/pose_graph/map_builder_2d.h"
#include "fusemap/pose_graph/pose_graph_2d.h"
#include "fusemap/sensor/sensor_types.h"

namespace fusemap {
namespace io {

// How far a TrajectoryArchive has got: the files' lengths and what the next segment of the
// densified trajectory continues from. Stored in checkpoints, so that a resume cuts the files
// back to what the restored state knows.
struct TrajectoryArchiveMark {
  std::uint64_t trajectory_bytes = 0;
  std::uint64_t nodes_bytes = 0;
  std::uint64_t odometry_bytes = 0;
  bool has_last_node = false;  // the newest archived node
  pose_graph::ArchivedNode2D last_node;
  // The last archived odometry sample before last_node (interpolation at its stamp needs it).
  bool has_carry = false;
  sensor::OdometryData carry;
  // Newest stamps written to trajectory.tum and odometry.tum (TUM needs increasing time).
  double last_output_stamp_s = -std::numeric_limits<double>::infinity();
  double last_odometry_stamp_s = -std::numeric_limits<double>::infinity();
};

// The settled part of a long run's outputs, streamed to disk as the pose graph archives
// trimmed nodes (PoseGraph2D::TakeTrimmedPrefix), so that the daemon's memory does not follow
// its run length. Three append-only TUM files in one folder: trajectory.tum (a pose per odometry
// sample, pose_graph::DensifyWithOdometry), nodes.tum and odometry.tum (the input). What is
// archived followed by Continue...() over the rest equals, sample for sample, one
// DensifyWithOdometry over the whole run. Each Append is flushed and fsynced.
class TrajectoryArchive {
 public:
  using TimedPose2d = pose_graph::MapBuilder2D::TimedPose2d;

  // Creates `dir` and empty files, or with `mark` (a resume) cuts existing files back to it.
  // If a file is shorter than its mark (lost, or not this checkpoint's), the archive starts
  // over empty, continuing from the mark's last node, and *warning says so: the run's outputs
  // then miss what was archived before. Null only if the files cannot be written.
  static std::unique_ptr<TrajectoryArchive> Open(const std::string& dir,
                                                 const TrajectoryArchiveMark* mark,
                                                 std::string* warning, std::string* error);
  ~TrajectoryArchive();
  TrajectoryArchive(const TrajectoryArchive&) = delete;
  TrajectoryArchive& operator=(const TrajectoryArchive&) = delete;

  // Appends `nodes` (just archived, oldest first, after every node archived before) and the
  // odometry they settle: the samples before the newest node's stamp, which are removed from
  // *odometry. `odometry` is the time-ordered record since the previous Append; nodes must not be
  // newer than its last sample.
  bool Append(const std::vector<pose_graph::ArchivedNode2D>& nodes,
              std::vector<sensor::OdometryData>* odometry, std::string* error);

  // The whole run's outputs: the archived files followed by `nodes` (the graph's remaining
  // nodes) and `odometry` (the record since the last Append), densified from the last archived
  // node on.
  bool ReadWholeRun(const std::vector<TimedPose2d>& nodes,
                    const std::vector<sensor::OdometryData>& odometry,
                    eval::Trajectory* trajectory, eval::Trajectory* all_nodes,
                    eval::Trajectory* all_odometry, std::string* error) const;

  const TrajectoryArchiveMark& mark() const { return mark_; }
  const std::string& dir() const { return dir_; }

 private:
  struct Files;
  TrajectoryArchive(std::string dir, TrajectoryArchiveMark mark, std::unique_ptr<Files> files);
  // Nodes and odometry for DensifyWithOdometry from the last archived node on.
  std::vector<TimedPose2d> WithLastNode(const std::vector<TimedPose2d>& nodes) const;
  std::vector<sensor::OdometryData> WithCarry(const std::vector<sensor::OdometryData>& odometry) const;

  const std::string dir_;
  TrajectoryArchiveMark mark_;
  std::unique_ptr<Files> files_;
};

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_TRAJECTORY_ARCHIVE_H_
