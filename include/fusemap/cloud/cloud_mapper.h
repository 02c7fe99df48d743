#ifndef FUSEMAP_CLOUD_CLOUD_MAPPER_H_
#define FUSEMAP_CLOUD_CLOUD_MAPPER_H_

#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <vector>

#include "fusemap/cloud/cloud_binder.h"
#include "fusemap/cloud/frame_cloud.h"
#include "fusemap/cloud/free_column_filter.h"
#include "fusemap/cloud/pose_interpolator.h"
#include "fusemap/common/config_reader.h"
#include "fusemap/common/rigid_transform.h"
#include "fusemap/sensor/rgbd_frame.h"

namespace fusemap {
namespace cloud {

struct CloudMapperOptions {
  bool enabled = true;
  // At most one frame per interval is turned into a cloud: filtering costs tens of ms a frame,
  // and consecutive frames at 10-25 Hz see nearly the same surfaces. The others still carve
  // free space (projective carving, a few ms), so moving people are removed at the full rate.
  double min_frame_interval_s = 0.0;
  // Frames waiting for a laser pose newer than themselves; beyond this the oldest is dropped.
  int max_pending_frames = 32;
  // Camera on the robot base. Without it the extrinsic each frame carries is used.
  bool override_extrinsic = false;
  std::vector<double> T_base_camera_xyz_m = {0.0, 0.0, 0.0};
  std::vector<double> T_base_camera_rpy_deg = {0.0, 0.0, 0.0};
  double octomap_resolution_m = 0.05;
  FrameCloudOptions frame;
  PoseInterpolatorOptions sync;
  CloudBinderOptions binder;
  // Applied to the map when it is written out, against the laser map (see the header).
  FreeColumnFilterOptions laser_free_space;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

// Keys: enabled, min_frame_interval_s, max_pending_frames, override_extrinsic,
// T_base_camera_xyz_m, T_base_camera_rpy_deg (roll, pitch, yaw about x, y, z of the optical
// frame's parent), octomap_resolution_m, frame, sync, binder, laser_free_space.
CloudMapperOptions ParseCloudMapperOptions(common::ConfigReader& reader);

// The camera's mount on the robot base for `frame`: the configured one with
// override_extrinsic, else the one the frame carries.
common::Rigid3d CameraExtrinsic(const CloudMapperOptions& options, const sensor::RgbdFrame& frame);

struct CloudMapperStats {
  int64_t frames_in = 0;
  int64_t frames_bound = 0;
  int64_t frames_skipped_rate = 0;     // within min_frame_interval_s of the last bound frame
  int64_t frames_carved = 0;           // depth images used for free-space carving
  int64_t frames_dropped_no_pose = 0;  // no laser pose could be interpolated in time
  int64_t frames_dropped_queue = 0;    // pending queue full
  int64_t frames_dropped_no_submap = 0;  // taken before the first submap existed
  int64_t frames_empty = 0;            // nothing left after filtering
  FrameCloudStats last_frame;
};

// A submap's pose in the map frame, by pose-graph index.
struct SubmapPose2d {
  int submap = 0;
  common::Rigid2d T_map_submap;
};

// Feeds RGB-D frames into the cloud binder at the pose local SLAM had when they were taken:
// each frame waits until a laser pose at or after its stamp arrives, is interpolated between
// the bracketing poses (never the nearest one), bound to the submap that was active then, and
// stays in that submap's frame. Clouds are bound with local-frame poses, which global SLAM
// never changes; global SLAM only moves submaps, reported through PlaceSubmaps.
// Not thread-safe: one owner (session::CloudStage, on its caller's thread or fusemapd's RGB-D
// thread).
class CloudMapper {
 public:
  explicit CloudMapper(const CloudMapperOptions& options);
  CloudMapper(const CloudMapper&) = delete;
  CloudMapper& operator=(const CloudMapper&) = delete;

  // Local SLAM's pose of the tracking frame (the robot base) at a scan, and the submap (by
  // pose-graph index, with its fixed local pose) that frames taken from now on bind to.
  // Processes frames it unblocks.
  void AddLocalPose(double stamp_s, const common::Rigid2d& T_local_tracking, int submap_id,
                    const common::Rigid2d& T_local_submap);
  // Submaps global SLAM placed or moved (pose_graph::PoseGraph2D::TakeSubmapPlacements decides
  // what moved): new submaps are placed, known ones have only their own regions re-posed.
  void PlaceSubmaps(const std::vector<SubmapPose2d>& placements);
  // Queues a frame; it is processed once the laser poses around its stamp are known.
  void AddFrame(const sensor::RgbdFrame& frame);
  // End of input: frames still waiting for a later pose can never get one and are dropped.
  void Finish();

  const CloudBinder& binder() const { return binder_; }
  const CloudMapperStats& stats() const { return stats_; }
  const PoseInterpolator& interpolator() const { return interpolator_; }
  const CloudMapperOptions& options() const { return options_; }
  int pending_frames() const { return static_cast<int>(pending_.size()); }
  // Where each submap's clouds are placed now, by pose-graph index.
  const std::map<int, common::Rigid2d>& T_map_submaps() const { return T_map_submaps_; }

 private:
  struct Binding {
    double stamp_s;
    int submap_id;
    common::Rigid2d T_local_submap;
  };

  // Handles queued frames in stamp order until the oldest must keep waiting.
  void ProcessPending();
  struct PendingFrame {
    sensor::RgbdFrame frame;  // carve-only frames keep no colour image
    bool bind;                // false: within min_frame_interval_s, only carves
  };
  void Bind(const PendingFrame& pending, const common::Rigid2d& T_local_tracking);
  const Binding* BindingAt(double stamp_s) const;

  const CloudMapperOptions options_;
  CloudBinder binder_;
  PoseInterpolator interpolator_;
  std::deque<Binding> bindings_;  // time-ordered, trimmed like the interpolator's history
  std::deque<PendingFrame> pending_;
  std::map<int, common::Rigid2d> T_map_submaps_;  // as last placed in the binder
  double newest_stamp_s_ = -1e300;
  double last_accepted_stamp_s_ = -1e300;
  bool finished_ = false;
  CloudMapperStats stats_;
};

}  // namespace cloud
}  // namespace fusemap

#endif  // FUSEMAP_CLOUD_CLOUD_MAPPER_H_
