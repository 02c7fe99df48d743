#ifndef FUSEMAP_DAEMON_MAP_OUTPUTS_H_
#define FUSEMAP_DAEMON_MAP_OUTPUTS_H_

#include <string>
#include <vector>

#include "fusemap/eval/trajectory.h"
#include "fusemap/pose_graph/map_builder_2d.h"
#include "fusemap/sensor/sensor_types.h"

namespace fusemap {
namespace daemon {

// Time-ordered poses as a TUM trajectory, skipping repeated stamps (TUM needs increasing time).
eval::Trajectory ToTrajectory(const std::vector<pose_graph::MapBuilder2D::TimedPose2d>& poses);

// The outputs fusemap_offline writes, from the same inputs: DIR/trajectory.tum (a pose per
// odometry sample, pose_graph::DensifyWithOdometry), DIR/nodes.tum, DIR/map.pgm + DIR/map.yaml
// (map_server) and DIR/map.png (map with trajectory). `odometry` is in arrival order without
// samples that went back in time. The builder must be idle (after Finish()).
bool WriteMapOutputs(const pose_graph::MapBuilder2D& builder,
                     const std::vector<sensor::OdometryData>& odometry, double resolution_m,
                     const std::string& dir, std::string* error);

}  // namespace daemon
}  // namespace fusemap

#endif  // FUSEMAP_DAEMON_MAP_OUTPUTS_H_
