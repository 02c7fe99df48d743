#ifndef FUSEMAP_DAEMON_PUBLISHER_H_
#define FUSEMAP_DAEMON_PUBLISHER_H_

#include <string>

#include "fusemap/common/rigid_transform.h"
#include "fusemap/daemon/health.h"
#include "fusemap/io/lcm_output_conversions.h"
#include "fusemap/io/trajectory_archive.h"
#include "fusemap/pose_graph/map_builder_2d.h"
#include "fusemap/pose_graph/pose_graph_snapshot.h"

namespace fusemap {
namespace daemon {

// Where the engine's outputs go. PublishPose is called only from the engine's SLAM thread, the
// others only from its report thread, so the two may run at the same time. LcmPublisher puts
// them on the wire; tests record them.
class Publisher {
 public:
  virtual ~Publisher() = default;
  // T_map_tracking of the scan stamped `stamp_s`.
  virtual void PublishPose(double stamp_s, const common::Rigid2d& T_map_tracking) = 0;
  virtual void PublishSubmapList(double stamp_s, const pose_graph::PoseGraphSnapshot& snapshot) = 0;
  // `note`: the newest decision of the visual loop checker (source "laser", decision "" without).
  virtual void PublishLoopClosure(double stamp_s, int new_loop_closures,
                                  const pose_graph::PoseGraph2D::Stats& stats, int latest_node,
                                  const io::LoopNote& note) = 0;
  virtual void PublishHealth(double stamp_s, const HealthReport& report) = 0;
};

// What a checkpoint holds besides the builder's state; null members are stored empty.
struct RunRecord {
  const std::vector<sensor::OdometryData>* odometry = nullptr;
  const io::TrajectoryArchiveMark* archive = nullptr;
};

// Where "write the state every checkpoint_period_s and at shutdown" plugs in. Save is called
// on the local SLAM thread between two messages (no scan in flight), after waiting for the
// executor to be idle, so the builder's state is consistent.
class Checkpointer {
 public:
  virtual ~Checkpointer() = default;
  virtual bool Save(pose_graph::MapBuilder2D& builder, const RunRecord& record,
                    std::string* error) = 0;
};

}  // namespace daemon
}  // namespace fusemap

#endif  // FUSEMAP_DAEMON_PUBLISHER_H_
