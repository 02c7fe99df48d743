#ifndef FUSEMAP_SESSION_CLOUD_STAGE_H_
#define FUSEMAP_SESSION_CLOUD_STAGE_H_

#include <cstddef>
#include <vector>

#include "fusemap/cloud/cloud_mapper.h"
#include "fusemap/common/rigid_transform.h"
#include "fusemap/sensor/rgbd_frame.h"

namespace fusemap {
namespace session {

// What SLAM tells the cloud after a scan, after an optimisation and at the end: a value, so
// the cloud may run on another thread and share no mutable state with SLAM.
struct CloudPoseUpdate {
  // Submaps to place or re-place first (pose_graph::PoseGraph2D::TakeSubmapPlacements).
  std::vector<cloud::SubmapPose2d> placements;
  // The scan's local pose, and the submap frames taken from now on bind to; -1: no scan pose.
  int submap_id = -1;
  double stamp_s = 0.0;
  common::Rigid2d T_local_tracking;
  common::Rigid2d T_local_submap;
  // The pose-graph node of the scan, or the newest before it (MapBuilder2D::ScanResult::node):
  // what the visual loop checker tags its keyframes with.
  int node_id = -1;

  bool empty() const { return placements.empty() && submap_id < 0; }
};

// What the cloud stage cost, for fusemap_offline's cloud_cost line: one entry per bound frame
// and per applied placement. Kept only when asked for (a daemon running for days would grow it).
struct CloudStageCost {
  std::vector<double> frame_ms;   // per bound frame (a call may bind several, or none)
  std::vector<double> update_ms;  // per PlaceSubmaps
  double total_s = 0.0;
  double final_update_ms = 0.0;   // the placements after the final optimisation
  size_t final_update_regions = 0;
  size_t final_update_points = 0;
};

// The RGB-D half of the pipeline: the cloud mapper fed with SLAM's pose updates and the
// camera's frames. Not thread-safe: one owner (SlamSession inline, or fusemapd's RGB-D thread).
class CloudStage {
 public:
  CloudStage(const cloud::CloudMapperOptions& options, bool record_cost);

  void Apply(const CloudPoseUpdate& update);
  void AddFrame(const sensor::RgbdFrame& frame);
  // End of input: the last update (the final optimisation's placements; empty if it was
  // applied already), then frames still waiting for a later pose are dropped.
  void Finish(const CloudPoseUpdate& last_update = CloudPoseUpdate());

  const cloud::CloudMapper& mapper() const { return mapper_; }
  const CloudStageCost& cost() const { return cost_; }

 private:
  template <typename F>
  void TimeFrames(F&& f);
  void Place(const std::vector<cloud::SubmapPose2d>& placements);

  cloud::CloudMapper mapper_;
  const bool record_cost_;
  CloudStageCost cost_;
};

}  // namespace session
}  // namespace fusemap

#endif  // FUSEMAP_SESSION_CLOUD_STAGE_H_
