#ifndef FUSEMAP_SESSION_VISUAL_STAGE_H_
#define FUSEMAP_SESSION_VISUAL_STAGE_H_

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "fusemap/cloud/cloud_mapper.h"
#include "fusemap/cloud/pose_interpolator.h"
#include "fusemap/io/visual_keyframes_file.h"
#include "fusemap/io/visual_loop_config.h"
#include "fusemap/pose_graph/pose_graph_2d.h"
#include "fusemap/sensor/rgbd_frame.h"
#include "fusemap/session/cloud_stage.h"
#include "fusemap/visual_loop/loop_arbiter.h"
#include "fusemap/visual_loop/visual_loop_checker.h"

namespace fusemap {
namespace session {

// A camera frame as the visual loop checker takes it: grey image, depth registered to it in
// metres (the cloud's depth-to-colour projection, cloud::RegisterDepthImage), the colour
// intrinsics and the camera mount as the cloud stage takes it (cloud::CameraExtrinsic).
// Empty image if the frame has no usable colour image.
visual_loop::CameraFrame ToCameraFrame(const sensor::RgbdFrame& frame,
                                       const cloud::CloudMapperOptions& camera,
                                       const visual_loop::KeyframeOptions& depth_range);

struct VisualStageStats {
  visual_loop::VisualLoopCheckerStats checker;  // keyframes, candidates, verified, refused
  int64_t frames_in = 0;
  int64_t frames_offered = 0;           // decoded and given to the checker
  int64_t frames_dropped_no_pose = 0;   // no laser pose could be interpolated in time
  int64_t frames_dropped_pending = 0;   // too many waiting for a pose
  int64_t frames_unusable = 0;          // no colour image
  int laser_loops_checked = 0;          // laser loops arbitrated
  int confirmed = 0;                    // laser_confirmed
  // Of those, held across a corridor only, with the camera's measurement added along it.
  int confirmed_along = 0;
  int overridden = 0;                   // visual_override
  int forced = 0;                       // visual_forced
  int kept = 0;                         // laser_kept
  int rejected = 0;                     // laser_rejected
  int visual_rejected = 0;              // visual_rejected
  // Keyframes whose motion from the keyframe before joined the graph as a node link, and
  // those whose motion the camera did not verify or measured too far from local SLAM's.
  int motion_links = 0;
  int motion_links_refused = 0;
  // Of the motion links, those measured on the keyframes' pixels (motion_links.refine_on_pixels).
  int motion_links_refined = 0;
};

// "visual_loop: keyframes=… candidates=… verified=… refused=… laser_loops_checked=…
// laser_confirmed=… confirmed_along=… visual_override=… visual_forced=… laser_kept=…
// laser_rejected=… visual_rejected=… motion_links=… motion_links_refused=…
// motion_links_refined=… frames_in=…
// frames_offered=… frames_dropped=…" (no newline): fusemap_offline's line.
std::string VisualSummaryLine(const VisualStageStats& stats);

// The visual half of loop closure (issue 17): the ORB visual loop checker fed with camera
// frames at local SLAM's pose, tagged with the pose-graph node and submap they belong to, and
// its decisions applied to the pose graph through its loop-constraint API:
// - each new laser loop (PoseGraph2D::TakeNewLoopClosures) is checked against the keyframes
//   nearest its node and its submap (VisualLoopChecker::CheckPlace) and arbitrated
//   (visual_loop::ArbitrateLoop): confirmed (source both), overridden (the visual measurement
//   replaces it), kept, or rejected (removed);
// - each visual loop the checker finds by appearance alone is arbitrated against a laser loop
//   of the same node/submap pair if there is one, and otherwise forced into the graph unless
//   the correction it asks is more than drift explains (rejected).
// - with motion links on (config.motion_links), each new keyframe is verified against the
//   keyframe before it, and the camera's motion between them joins the graph as a node link
//   (PoseGraph2D::AddNodeLink) unless it differs from local SLAM's by more than a wrong match
//   would.
// Every decision is recorded (records(), DIR/loops.tsv). A laser loop waits until the frames
// up to its node have been seen (or max_node_gap more nodes came), so that its place has
// keyframes. Keyframes of trimmed submaps are released.
// Not thread-safe: one owner (SlamSession inline, or fusemapd's visual thread); the pose graph
// is thread-safe.
class VisualStage {
 public:
  // `config` must be enabled with its vocabulary loaded; `camera` gives the extrinsic and the
  // time synchronisation (cloud.sync) the cloud stage uses. `graph` outlives the stage.
  VisualStage(const io::VisualLoopConfig& config, const cloud::CloudMapperOptions& camera,
              pose_graph::PoseGraph2D* graph);
  VisualStage(const VisualStage&) = delete;
  VisualStage& operator=(const VisualStage&) = delete;

  // SLAM's pose after a scan (as the cloud stage gets it; placements are ignored).
  void Apply(const CloudPoseUpdate& update);
  void AddFrame(const sensor::RgbdFrame& frame);
  // End of input: frames still waiting for a pose are dropped, every laser loop still waiting
  // is arbitrated.
  void Finish();

  // Checkpoints: the keyframes and where their bases stood relative to their nodes. Restore
  // only before any input (the counters and records restart).
  io::VisualKeyframesState ExportState() const;
  void RestoreState(io::VisualKeyframesState state);

  const std::vector<visual_loop::ArbitrationRecord>& records() const { return records_; }
  VisualStageStats stats() const;
  const visual_loop::VisualLoopChecker& checker() const { return checker_; }

  // Called before each piece of the checker's work (a frame's keyframe processing, one place
  // verification), so that an owner on another thread can hold it until the CPU is free of
  // more urgent work (fusemapd: right after a scan's pose). Empty: run at once.
  void SetPacer(std::function<void()> pace) { pace_ = std::move(pace); }

 private:
  // Where a keyframe's robot base stood relative to its node (both local SLAM poses).
  struct KeyframeInfo {
    int node = -1;
    int submap = -1;
    common::Rigid2d T_node_base;
  };
  struct Binding {
    double stamp_s;
    int node;
    int submap;
    common::Rigid2d T_local_node;
  };

  void Pace() const {
    if (pace_) pace_();
  }
  void ProcessPending();
  void Offer(const sensor::RgbdFrame& frame, const common::Rigid2d& T_local_base);
  void HandleVisualLoop(const visual_loop::VisualLoopConstraint& loop);
  // Verifies keyframe `id` against the keyframe before it and adds the motion between them to
  // the graph as a node link (config.motion_links).
  void LinkMotion(int id, const common::Rigid2d& T_local_base);
  // Arbitrates the waiting laser loops whose place the camera has had its chance to see.
  void ProcessLaserLoops(bool all);
  void CheckLaserLoop(const pose_graph::LoopClosure2D& loop);
  void Apply(const visual_loop::ArbitrationRecord& record, int laser_id);
  // Where keyframe `id`'s base stands in `submap` by the current estimate.
  std::optional<common::Rigid2d> T_submap_base(int submap, int id) const;
  // The path between two nodes by the graph's current poses (over the nodes it still holds).
  double PathLengthM(int node_a, int node_b) const;
  // A node-in-submap measurement of `node` from one of keyframe `id`'s base.
  std::optional<visual_loop::LoopMeasurement2D> ForNode(
      const visual_loop::LoopMeasurement2D& base_measurement, int id, int submap,
      int node) const;
  void ReleaseTrimmedSubmaps();
  const Binding* BindingAt(double stamp_s) const;

  const io::VisualLoopConfig config_;
  const cloud::CloudMapperOptions camera_;
  pose_graph::PoseGraph2D* const graph_;
  visual_loop::VisualLoopChecker checker_;
  cloud::PoseInterpolator interpolator_;
  std::deque<Binding> bindings_;  // time-ordered, as long as the interpolator's history
  std::deque<sensor::RgbdFrame> pending_;
  std::map<int, KeyframeInfo> keyframes_;  // by keyframe id
  std::deque<pose_graph::LoopClosure2D> laser_loops_;  // waiting for their place's frames
  std::vector<visual_loop::ArbitrationRecord> records_;
  double newest_stamp_s_ = -1e300;
  double last_keyframe_stamp_s_ = -1e300;
  // The newest keyframe and its base's local SLAM pose (-1: none since the start or a resume).
  int last_keyframe_id_ = -1;
  common::Rigid2d T_local_last_keyframe_base_;
  int newest_node_ = -1;
  int newest_offered_node_ = -1;
  bool finished_ = false;
  VisualStageStats stats_;
  std::function<void()> pace_;
};

}  // namespace session
}  // namespace fusemap

#endif  // FUSEMAP_SESSION_VISUAL_STAGE_H_
