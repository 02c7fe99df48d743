#ifndef FUSEMAP_IO_TRAJECTORY_ARCHIVE_H_
#define FUSEMAP_IO_TRAJECTORY_ARCHIVE_H_

#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "fusemap/pose_graph/map_builder_2d.h"
#include "fusemap/pose_graph/pose_graph_2d.h"
#include "fusemap/sensor/sensor_types.h"

namespace fusemap {
namespace io {

// How much a TrajectoryArchive holds. Stored in checkpoints, so that a resume cuts the files
// back to what the restored state knows.
struct TrajectoryArchiveMark {
  std::uint64_t nodes_bytes = 0;
  std::uint64_t odometry_bytes = 0;
  // Of the newest odometry sample archived: later samples must not go back before it.
  double last_odometry_stamp_s = -std::numeric_limits<double>::infinity();
};

// The part of a long run that the daemon no longer needs in memory, on disk: nodes the pose
// graph has trimmed and let go (PoseGraph2D::TakeTrimmedNodes; their poses are final) and the
// odometry record, which is only needed for the trajectory output. Two append-only files of
// little-endian binary records in one folder, so values come back bit for bit:
//   nodes.bin     i32 node index, f64 stamp_s, f64 x_m, f64 y_m, f64 angle_rad (36 bytes)
//   odometry.bin  f64 stamp_s, f64 x_m, f64 y_m, f64 angle_rad (32 bytes)
// At the end of the run ReadWholeRun merges them with what is still in memory, and the outputs
// are written from that exactly as without an archive. Each Append is fsynced.
class TrajectoryArchive {
 public:
  using TimedPose2d = pose_graph::MapBuilder2D::TimedPose2d;

  // Creates `dir` and empty files, or with `mark` (a resume) cuts existing files back to it.
  // If a file is shorter than its mark (lost, or not this checkpoint's), the archive starts
  // over empty and *warning says so: the run's outputs then miss what was archived before.
  // Null only if the files cannot be written.
  static std::unique_ptr<TrajectoryArchive> Open(const std::string& dir,
                                                 const TrajectoryArchiveMark* mark,
                                                 std::string* warning, std::string* error);
  ~TrajectoryArchive();
  TrajectoryArchive(const TrajectoryArchive&) = delete;
  TrajectoryArchive& operator=(const TrajectoryArchive&) = delete;

  // Appends `nodes` and the samples of *odometry (time-ordered, following those appended
  // before), then clears *odometry.
  bool Append(const std::vector<pose_graph::ArchivedNode2D>& nodes,
              std::vector<sensor::OdometryData>* odometry, std::string* error);

  // The whole run: the archived nodes and `nodes` (those still in the graph) in time order, and
  // the archived odometry followed by `odometry` (the record since the last Append). Damaged
  // files are errors naming the file and offset.
  bool ReadWholeRun(const std::vector<TimedPose2d>& nodes,
                    const std::vector<sensor::OdometryData>& odometry,
                    std::vector<TimedPose2d>* all_nodes,
                    std::vector<sensor::OdometryData>* all_odometry, std::string* error) const;

  const TrajectoryArchiveMark& mark() const { return mark_; }
  const std::string& dir() const { return dir_; }

 private:
  struct Files;
  TrajectoryArchive(std::string dir, TrajectoryArchiveMark mark, std::unique_ptr<Files> files);

  const std::string dir_;
  TrajectoryArchiveMark mark_;
  std::unique_ptr<Files> files_;
};

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_TRAJECTORY_ARCHIVE_H_
