#ifndef FUSEMAP_POSE_GRAPH_MAP_BUILDER_2D_H_
#define FUSEMAP_POSE_GRAPH_MAP_BUILDER_2D_H_

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fusemap/common/config_reader.h"
#include "fusemap/common/thread_pool.h"
#include "fusemap/mapping/local_trajectory_builder_2d.h"
#include "fusemap/pose_graph/map_builder_state_2d.h"
#include "fusemap/pose_graph/pose_graph_2d.h"

namespace fusemap {
namespace pose_graph {

struct MapBuilderOptions2D {
  mapping::LocalTrajectoryBuilderOptions2D local_slam;
  PoseGraphOptions2D global_slam;

  void Check(common::OptionChecker* check) const {
    check->Nested("local_slam", local_slam);
    check->Nested("global_slam", global_slam);
  }
  bool IsValid(std::string* error) const { return common::IsValidOptions(*this, error); }
};

// Keys: local_slam, global_slam.
MapBuilderOptions2D ParseMapBuilderOptions2D(common::ConfigReader& reader);

// One robot's 2D SLAM: local SLAM feeding nodes and submaps into global SLAM. Driven through
// session::SlamSession by both fusemap_offline and fusemapd.
class MapBuilder2D {
 public:
  struct TimedPose2d {
    double stamp_s;
    common::Rigid2d pose;
  };

  MapBuilder2D(const MapBuilderOptions2D& options, common::Executor* executor);
  MapBuilder2D(const MapBuilder2D&) = delete;
  MapBuilder2D& operator=(const MapBuilder2D&) = delete;

  void AddOdometry(const sensor::OdometryData& odometry) { local_.AddOdometry(odometry); }
  void AddImu(const sensor::ImuData& imu) { local_.AddImu(imu); }
  // See LocalTrajectoryBuilder2D::OnTimeReset; before the first message on the new time base.
  void OnTimeReset() { local_.OnTimeReset(); }
  struct ScanResult {
    common::Rigid2d T_map_tracking;  // the global estimate at the scan
    common::Rigid2d T_local_tracking;
    // The submap data taken at this time binds to (the oldest active one, the one scans are
    // matched against), by pose-graph index, with its fixed local pose; -1 if none yet.
    int submap_id = -1;
    common::Rigid2d T_local_submap;
    // The pose-graph node this scan became, or if it was not inserted the newest node before
    // it; -1 before the first.
    int node = -1;
  };
  // Empty if the scan was unusable.
  std::optional<ScanResult> AddScan(const sensor::LaserScan& scan);
  // Waits for background work and runs the final optimisation.
  void Finish() { pose_graph_.RunFinalOptimization(); }

  // Node poses in the map frame, in time order.
  std::vector<TimedPose2d> NodePoses() const;
  const mapping::LocalTrajectoryBuilder2D& local_slam() const { return local_; }
  PoseGraph2D& pose_graph() { return pose_graph_; }
  const PoseGraph2D& pose_graph() const { return pose_graph_; }

  // A consistent snapshot of everything mapped so far (checkpoints). Call it from the thread
  // that feeds the builder (it copies the active submaps that AddScan writes); the global
  // optimiser may keep running meanwhile: its work in flight is recorded, not waited for.
  MapBuilderState2D ExportState() const;
  // A builder that continues exactly where the one that exported `state` stopped: same
  // submaps, graph, loop-closure sampling and local SLAM state (extrapolator included), so
  // with an InlineExecutor it produces the same poses as the original would have.
  // `state` must satisfy MapBuilderState2D's invariants.
  static std::unique_ptr<MapBuilder2D> Restore(const MapBuilderOptions2D& options,
                                               common::Executor* executor,
                                               const MapBuilderState2D& state);

 private:
  mapping::LocalTrajectoryBuilder2D local_;
  PoseGraph2D pose_graph_;
  int newest_node_ = -1;  // ScanResult::node
};

// Poses at every odometry sample (how Kümmerle et al. 2009 evaluate between-node times): the
// odometry increment from each of the two neighbouring nodes composed onto that node's pose,
// the two predictions blended by time fraction, so the pose is continuous and equals each node
// at its stamp. Samples before the first or after the last node use the nearest node only.
// Repeated odometry stamps keep the first sample. Without odometry the nodes are returned.
// `breaks_s`: stamps of the first odometry samples after time resets, where the odometry
// restarts (a looping log): no increment is taken across one, so between two nodes on either
// side each sample follows the node on its own side.
std::vector<MapBuilder2D::TimedPose2d> DensifyWithOdometry(
    const std::vector<MapBuilder2D::TimedPose2d>& nodes,
    const std::vector<sensor::OdometryData>& odometry, const std::vector<double>& breaks_s = {});

}  // namespace pose_graph
}  // namespace fusemap

#endif  // FUSEMAP_POSE_GRAPH_MAP_BUILDER_2D_H_
