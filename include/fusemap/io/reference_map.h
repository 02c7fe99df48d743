#ifndef FUSEMAP_IO_REFERENCE_MAP_H_
#define FUSEMAP_IO_REFERENCE_MAP_H_

#include <Eigen/Core>
#include <string>
#include <vector>

#include "fusemap/eval/trajectory.h"
#include "fusemap/io/map_writer.h"
#include "fusemap/io/slam_config.h"

namespace fusemap {
namespace io {

// What RenderLogAtPoses drew.
struct ReferenceMap {
  MapImage map;
  std::vector<Eigen::Vector2d> trajectory_xy;  // the poses used, in the map frame
  int scans_read = 0;
  int scans_used = 0;  // scans with a pose at their stamp
};

// Draws the laser scans of an LCM log placed at given poses (for example GMapping's, from
// fusemap_carmen2lcm --reference-poses) into an occupancy map with the SLAM's own code and
// the profile's settings: range gate, laser mounting, submap size, resolution and odds update,
// each scan in the newest two of grids started every `submaps.num_range_data` scans, rendered
// together as fusemap_offline renders its submaps. So a reference layout and our map show the same scans the same way, at the same
// scale. poses: T_map_tracking per scan stamp (within 1 ms); T_out_map moves the whole drawing
// (for example onto our first node, so both maps start at the same pose).
bool RenderLogAtPoses(const std::string& log_path, const SlamConfig& config,
                      const eval::Trajectory& poses, const common::Rigid2d& T_out_map,
                      ReferenceMap* out, std::string* error);

// The motion T_anchor_poses that puts `poses` at the anchor's first stamp onto the anchor's
// first pose (in the plane), so that two trajectories start together; false if `poses` has no
// pose within 1 ms of that stamp.
bool AnchorOnFirstPose(const eval::Trajectory& poses, const eval::Trajectory& anchor,
                       common::Rigid2d* T_anchor_poses);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_REFERENCE_MAP_H_
