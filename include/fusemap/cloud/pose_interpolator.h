#ifndef FUSEMAP_CLOUD_POSE_INTERPOLATOR_H_
#define FUSEMAP_CLOUD_POSE_INTERPOLATOR_H_

#include <algorithm>
#include <cstdint>
#include <deque>
#include <string>

#include "fusemap/common/config_reader.h"
#include "fusemap/common/rigid_transform.h"

namespace fusemap {
namespace cloud {

// Config keys (same names): max_history_s (poses older than the newest minus this are
// forgotten), max_gap_s (largest gap between two poses that may be interpolated across),
// hold_s (how long a frame may wait for a pose newer than itself).
struct PoseInterpolatorOptions {
  double max_history_s = 30.0;
  double max_gap_s = 0.5;
  double hold_s = 0.5;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

PoseInterpolatorOptions ParsePoseInterpolatorOptions(common::ConfigReader& reader);

// Time synchronisation between the laser pose stream and camera frames: keeps a bounded,
// strictly time-ordered history of local SLAM's planar poses of the tracking frame (the robot
// base, which the camera extrinsics T_base_camera are given in) and interpolates the pose at a
// frame's stamp between the two samples that bracket it (linear translation, shortest-arc yaw),
// never the nearest sample. The 3D camera pose in the local frame is then
// Rigid3d::FromRigid2d(T_local_tracking) * T_base_camera.
class PoseInterpolator {
 public:
  enum class Status {
    kReady,  // `T_local_tracking` holds the interpolated pose.
    kWait,   // The stamp is newer than every pose, and the frame has not waited hold_s yet.
    kDrop,   // No pose can be had: too old, bracketing gap too large, or waited too long.
  };
  struct Result {
    Status status = Status::kDrop;
    common::Rigid2d T_local_tracking;
  };

  explicit PoseInterpolator(const PoseInterpolatorOptions& options);

  // Appends a pose. Stamps must strictly increase; an out-of-order or duplicate stamp is
  // rejected (returns false) and counted. Trims the history to max_history_s.
  bool AddPose(double stamp_s, const common::Rigid2d& T_local_tracking);

  // The pose at stamp_s. `now_s` is the caller's current time in the same time base as the
  // stamps (newest sensor stamp seen, or the clock in a live system); a frame waits while
  // now_s - stamp_s <= hold_s. Each kDrop is counted by reason: the caller discards a dropped
  // frame, so each frame is counted once.
  Result Lookup(double stamp_s, double now_s);

  size_t size() const { return poses_.size(); }
  bool empty() const { return poses_.empty(); }
  double oldest_stamp_s() const;
  double newest_stamp_s() const;
  int64_t num_rejected_poses() const { return num_rejected_poses_; }
  int64_t num_dropped_too_old() const { return num_dropped_too_old_; }
  int64_t num_dropped_gap() const { return num_dropped_gap_; }
  int64_t num_dropped_timeout() const { return num_dropped_timeout_; }

 private:
  struct TimedPose {
    double stamp_s;
    common::Rigid2d T_local_tracking;
  };

  Result Drop(int64_t* counter);

  PoseInterpolatorOptions options_;
  std::deque<TimedPose> poses_;  // Strictly increasing stamps.
  int64_t num_rejected_poses_ = 0;
  int64_t num_dropped_too_old_ = 0;
  int64_t num_dropped_gap_ = 0;
  int64_t num_dropped_timeout_ = 0;
};

// The consumers of camera frames (CloudMapper, session::VisualStage) queue each frame until
// the laser pose after it is known; these two helpers are that queue's logic, written once.
//
// Hands the queued frames, oldest first, their interpolated pose: ready(frame, T_local_tracking)
// or, if no pose can be had, dropped(frame); stops at the first that must keep waiting.
// `newest_stamp_s` is the newest laser stamp seen; once `finished`, no later pose will come,
// so nothing waits any more. stamp_of(frame) gives a queued frame's stamp.
template <typename Frame, typename StampOf, typename Ready, typename Dropped>
void DrainPendingFrames(std::deque<Frame>* pending, PoseInterpolator* interpolator,
                        double newest_stamp_s, bool finished, double hold_s, StampOf&& stamp_of,
                        Ready&& ready, Dropped&& dropped) {
  while (!pending->empty()) {
    const double stamp_s = stamp_of(pending->front());
    const double now_s = finished ? stamp_s + hold_s + 1.0 : newest_stamp_s;
    const PoseInterpolator::Result result = interpolator->Lookup(stamp_s, now_s);
    if (result.status == PoseInterpolator::Status::kWait) return;
    if (result.status == PoseInterpolator::Status::kReady) {
      ready(pending->front(), result.T_local_tracking);
    } else {
      dropped(pending->front());
    }
    pending->pop_front();
  }
}

// The latest of time-ordered entries (members stamp_s) at or before `stamp_s`; the first if
// all are later, null if there are none: which submap a frame taken then binds to.
template <typename Entry>
const Entry* LatestAtOrBefore(const std::deque<Entry>& entries, double stamp_s) {
  const auto it = std::upper_bound(
      entries.begin(), entries.end(), stamp_s,
      [](double stamp, const Entry& entry) { return stamp < entry.stamp_s; });
  if (it == entries.begin()) return entries.empty() ? nullptr : &entries.front();
  return &*std::prev(it);
}

}  // namespace cloud
}  // namespace fusemap

#endif  // FUSEMAP_CLOUD_POSE_INTERPOLATOR_H_
