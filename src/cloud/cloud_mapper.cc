#include "fusemap/cloud/cloud_mapper.h"

#include <algorithm>
#include <cmath>

#include "fusemap/common/math.h"

namespace fusemap {
namespace cloud {

common::Rigid3d CameraExtrinsic(const CloudMapperOptions& options,
                                const sensor::RgbdFrame& frame) {
  if (!options.override_extrinsic) return frame.T_base_color;
  const auto& xyz = options.T_base_camera_xyz_m;
  const auto& rpy = options.T_base_camera_rpy_deg;
  const Eigen::Quaterniond rotation =
      Eigen::AngleAxisd(common::DegToRad(rpy[2]), Eigen::Vector3d::UnitZ()) *
      Eigen::AngleAxisd(common::DegToRad(rpy[1]), Eigen::Vector3d::UnitY()) *
      Eigen::AngleAxisd(common::DegToRad(rpy[0]), Eigen::Vector3d::UnitX());
  return common::Rigid3d(Eigen::Vector3d(xyz[0], xyz[1], xyz[2]), rotation);
}

void CloudMapperOptions::Check(common::OptionChecker* check) const {
  check->Require(min_frame_interval_s >= 0.0, "min_frame_interval_s", "must be >= 0");
  check->Require(max_pending_frames >= 1, "max_pending_frames", "must be >= 1");
  check->Require(T_base_camera_xyz_m.size() == 3, "T_base_camera_xyz_m", "needs 3 numbers");
  check->Require(T_base_camera_rpy_deg.size() == 3, "T_base_camera_rpy_deg", "needs 3 numbers");
  check->Require(octomap_resolution_m >= 0.005 && octomap_resolution_m <= 2.0,
                 "octomap_resolution_m", "must be in [0.005, 2]");
  check->Nested("frame", frame);
  check->Nested("sync", sync);
  check->Nested("binder", binder);
  check->Nested("laser_free_space", laser_free_space);
}

bool CloudMapperOptions::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

CloudMapperOptions ParseCloudMapperOptions(common::ConfigReader& reader) {
  CloudMapperOptions options;
  reader.Get("enabled", &options.enabled);
  reader.Get("min_frame_interval_s", &options.min_frame_interval_s);
  reader.Get("max_pending_frames", &options.max_pending_frames);
  reader.Get("override_extrinsic", &options.override_extrinsic);
  reader.Get("T_base_camera_xyz_m", &options.T_base_camera_xyz_m);
  reader.Get("T_base_camera_rpy_deg", &options.T_base_camera_rpy_deg);
  reader.Get("octomap_resolution_m", &options.octomap_resolution_m);
  options.frame = ParseFrameCloudOptions(reader.Child("frame"));
  options.sync = ParsePoseInterpolatorOptions(reader.Child("sync"));
  options.binder = ParseCloudBinderOptions(reader.Child("binder"));
  options.laser_free_space = ParseFreeColumnFilterOptions(reader.Child("laser_free_space"));
  reader.CheckOptions(options);
  return options;
}

CloudMapper::CloudMapper(const CloudMapperOptions& options)
    : options_(options), binder_(options.binder), interpolator_(options.sync) {}

void CloudMapper::AddLocalPose(double stamp_s, const common::Rigid2d& T_local_tracking,
                               int submap_id, const common::Rigid2d& T_local_submap) {
  if (!interpolator_.AddPose(stamp_s, T_local_tracking)) return;  // Counted there.
  bindings_.push_back({stamp_s, submap_id, T_local_submap});
  if (T_map_submaps_.count(submap_id) == 0) {
    // Until global SLAM reports it, a new submap sits where local SLAM put it; the next
    // PlaceSubmaps moves it, and its clouds with it.
    T_map_submaps_[submap_id] = T_local_submap;
    binder_.SetSubmapPose(submap_id, common::Rigid3d::FromRigid2d(T_local_submap));
  }
  // Keep one binding older than the interpolator's history so every pose it can still
  // interpolate has the binding that was valid then.
  while (bindings_.size() > 1 && bindings_[1].stamp_s <= interpolator_.oldest_stamp_s()) {
    bindings_.pop_front();
  }
  newest_stamp_s_ = std::max(newest_stamp_s_, stamp_s);
  ProcessPending();
}

void CloudMapper::PlaceSubmaps(const std::vector<SubmapPose2d>& placements) {
  std::vector<std::pair<int, common::Rigid3d>> moved;
  for (const SubmapPose2d& placement : placements) {
    const auto it = T_map_submaps_.find(placement.submap);
    if (it == T_map_submaps_.end()) {
      T_map_submaps_[placement.submap] = placement.T_map_submap;
      binder_.SetSubmapPose(placement.submap,
                            common::Rigid3d::FromRigid2d(placement.T_map_submap));
    } else {
      it->second = placement.T_map_submap;
      moved.emplace_back(placement.submap, common::Rigid3d::FromRigid2d(placement.T_map_submap));
    }
  }
  if (!moved.empty()) binder_.OnSubmapsMoved(moved);
}

void CloudMapper::AddFrame(const sensor::RgbdFrame& frame) {
  ++stats_.frames_in;
  if (!options_.enabled) return;
  newest_stamp_s_ = std::max(newest_stamp_s_, frame.stamp_s);
  const bool bind = frame.stamp_s - last_accepted_stamp_s_ >= options_.min_frame_interval_s;
  const bool carve = options_.binder.remove_dynamic && !options_.binder.ray_carving;
  if (!bind) ++stats_.frames_skipped_rate;
  if (!bind && !carve) return;
  if (static_cast<int>(pending_.size()) >= options_.max_pending_frames) {
    // Losing a carve-only frame costs little (its neighbours carve too); keep frames to bind.
    auto victim = std::find_if(pending_.begin(), pending_.end(),
                               [](const PendingFrame& p) { return !p.bind; });
    pending_.erase(victim == pending_.end() ? pending_.begin() : victim);
    ++stats_.frames_dropped_queue;
  }
  if (bind) {
    // The rate limit counts from accepted frames: whether one binds is known only later.
    last_accepted_stamp_s_ = frame.stamp_s;
    pending_.push_back({frame, true});
  } else {
    PendingFrame depth_only{sensor::RgbdFrame(), false};
    depth_only.frame.stamp_s = frame.stamp_s;
    depth_only.frame.depth_intrinsics = frame.depth_intrinsics;
    depth_only.frame.T_color_depth = frame.T_color_depth;
    depth_only.frame.T_base_color = frame.T_base_color;
    depth_only.frame.depth_mm = frame.depth_mm;
    pending_.push_back(std::move(depth_only));
  }
  ProcessPending();
}

void CloudMapper::Finish() {
  finished_ = true;
  ProcessPending();
}

void CloudMapper::ProcessPending() {
  while (!pending_.empty()) {
    const sensor::RgbdFrame& frame = pending_.front().frame;
    // After the end of input no later pose will come, so waiting is pointless.
    const double now_s = finished_ ? frame.stamp_s + options_.sync.hold_s + 1.0 : newest_stamp_s_;
    const PoseInterpolator::Result result = interpolator_.Lookup(frame.stamp_s, now_s);
    if (result.status == PoseInterpolator::Status::kWait) return;
    if (result.status == PoseInterpolator::Status::kReady) {
      Bind(pending_.front(), result.T_local_tracking);
    } else {
      ++stats_.frames_dropped_no_pose;
    }
    pending_.pop_front();
  }
}

const CloudMapper::Binding* CloudMapper::BindingAt(double stamp_s) const {
  const auto it = std::upper_bound(
      bindings_.begin(), bindings_.end(), stamp_s,
      [](double stamp, const Binding& binding) { return stamp < binding.stamp_s; });
  if (it == bindings_.begin()) return bindings_.empty() ? nullptr : &bindings_.front();
  return &*std::prev(it);
}

void CloudMapper::Bind(const PendingFrame& pending, const common::Rigid2d& T_local_tracking) {
  const sensor::RgbdFrame& frame = pending.frame;
  const Binding* binding = BindingAt(frame.stamp_s);
  if (binding == nullptr) {
    ++stats_.frames_dropped_no_submap;
    return;
  }
  const common::Rigid3d T_base_color = CameraExtrinsic(options_, frame);
  const common::Rigid3d T_submap_tracking =
      common::Rigid3d::FromRigid2d(binding->T_local_submap.inverse() * T_local_tracking);
  if (options_.binder.remove_dynamic && !options_.binder.ray_carving) {
    binder_.CarveWithDepth(binding->submap_id, T_submap_tracking * T_base_color * frame.T_color_depth,
                           frame.depth_intrinsics, frame.depth_mm);
    ++stats_.frames_carved;
  }
  if (!pending.bind) return;
  CameraCloud cloud = BuildFrameCloud(frame, options_.frame, &stats_.last_frame);
  cloud.T_base_camera = T_base_color;
  if (!cloud.points_camera || cloud.points_camera->empty()) {
    ++stats_.frames_empty;
    return;
  }
  binder_.AddCloud(binding->submap_id, T_submap_tracking * cloud.T_base_camera, cloud);
  ++stats_.frames_bound;
}

}  // namespace cloud
}  // namespace fusemap
