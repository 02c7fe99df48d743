#include "fusemap/mapping/pose_extrapolator_2d.h"

#include <algorithm>

namespace fusemap {
namespace mapping {
namespace {
// Odometry older than this before the last pose is still kept so that the pose time itself
// can be interpolated.
constexpr double kOdometryHistoryMarginS = 1.0;
// Odometry velocity is held at most this long past the last sample.
constexpr double kMaxOdometryExtrapolationS = 0.5;
}  // namespace

PoseExtrapolator2D::PoseExtrapolator2D(double pose_queue_duration_s)
    : pose_queue_duration_s_(pose_queue_duration_s) {}

PoseExtrapolator2D::PoseExtrapolator2D(double pose_queue_duration_s,
                                       const PoseExtrapolatorState2D& state)
    : pose_queue_duration_s_(pose_queue_duration_s),
      odometry_(state.odometry.begin(), state.odometry.end()),
      imu_(state.imu.begin(), state.imu.end()),
      linear_velocity_mps_(state.linear_velocity_mps),
      angular_velocity_radps_(state.angular_velocity_radps) {
  for (const auto& p : state.poses) poses_.push_back({p.stamp_s, p.pose});
}

PoseExtrapolatorState2D PoseExtrapolator2D::ExportState() const {
  PoseExtrapolatorState2D state;
  for (const auto& p : poses_) state.poses.push_back({p.stamp_s, p.pose});
  state.odometry.assign(odometry_.begin(), odometry_.end());
  state.imu.assign(imu_.begin(), imu_.end());
  state.linear_velocity_mps = linear_velocity_mps_;
  state.angular_velocity_radps = angular_velocity_radps_;
  return state;
}

void PoseExtrapolator2D::AddPose(double stamp_s, const common::Rigid2d& T_local_tracking) {
  if (!poses_.empty() && stamp_s <= poses_.back().stamp_s) {
    // Same-time poses replace the previous estimate rather than producing an infinite velocity.
    if (stamp_s == poses_.back().stamp_s) poses_.back().pose = T_local_tracking;
    return;
  }
  poses_.push_back({stamp_s, T_local_tracking});
  // Velocity from the oldest pose still within the window: averages out scan-matching jitter.
  while (poses_.size() > 2 && poses_[1].stamp_s <= stamp_s - pose_queue_duration_s_) {
    poses_.pop_front();
  }
  if (poses_.size() >= 2) {
    const TimedPose& a = poses_.front();
    const TimedPose& b = poses_.back();
    const double dt = b.stamp_s - a.stamp_s;
    linear_velocity_mps_ = (b.pose.translation() - a.pose.translation()) / dt;
    angular_velocity_radps_ = common::NormalizeAngle(b.pose.angle_rad() - a.pose.angle_rad()) / dt;
  }
  TrimQueues();
}

bool PoseExtrapolator2D::AddOdometry(const sensor::OdometryData& odometry) {
  if (!odometry_.empty() && odometry.stamp_s < odometry_.back().stamp_s) return false;
  odometry_.push_back(odometry);
  TrimQueues();
  return true;
}

bool PoseExtrapolator2D::AddImu(const sensor::ImuData& imu) {
  if (!imu_.empty() && imu.stamp_s < imu_.back().stamp_s) return false;
  imu_.push_back(imu);
  TrimQueues();
  return true;
}

void PoseExtrapolator2D::ForgetMotion() {
  odometry_.clear();
  imu_.clear();
  if (poses_.size() > 1) poses_.erase(poses_.begin(), poses_.end() - 1);
  linear_velocity_mps_.setZero();
  angular_velocity_radps_ = 0.0;
}

void PoseExtrapolator2D::TrimQueues() {
  if (poses_.empty()) {
    // Without a pose nothing is extrapolated yet; keep only a short history.
    while (odometry_.size() > 2 && odometry_[1].stamp_s < odometry_.back().stamp_s - kOdometryHistoryMarginS) {
      odometry_.pop_front();
    }
    while (imu_.size() > 2 && imu_[1].stamp_s < imu_.back().stamp_s - kOdometryHistoryMarginS) {
      imu_.pop_front();
    }
    return;
  }
  const double keep_from_s = poses_.back().stamp_s - kOdometryHistoryMarginS;
  while (odometry_.size() > 2 && odometry_[1].stamp_s < keep_from_s) odometry_.pop_front();
  while (imu_.size() > 2 && imu_[1].stamp_s < keep_from_s) imu_.pop_front();
}

bool PoseExtrapolator2D::InterpolateOdometry(double stamp_s, common::Rigid2d* T_odom_base) const {
  if (odometry_.empty() || stamp_s < odometry_.front().stamp_s) return false;
  if (stamp_s >= odometry_.back().stamp_s) {
    // A scan usually arrives before the odometry sample that follows it. Over a short gap
    // the last odometry velocity is extrapolated; a longer gap means odometry stopped
    // reporting (logs that record it only while moving), so the robot is taken to be still.
    const double gap_s = stamp_s - odometry_.back().stamp_s;
    if (gap_s <= kMaxOdometryExtrapolationS && odometry_.size() >= 2) {
      const sensor::OdometryData& a = odometry_[odometry_.size() - 2];
      const sensor::OdometryData& b = odometry_.back();
      const double span_s = b.stamp_s - a.stamp_s;
      if (span_s > 1e-3 && span_s <= kMaxOdometryExtrapolationS) {
        const common::Rigid2d delta = a.pose.inverse() * b.pose;
        const double f = gap_s / span_s;
        *T_odom_base = b.pose * common::Rigid2d(f * delta.translation(), f * delta.angle_rad());
        return true;
      }
    }
    *T_odom_base = odometry_.back().pose;
    return true;
  }
  const auto it = std::upper_bound(
      odometry_.begin(), odometry_.end(), stamp_s,
      [](double t, const sensor::OdometryData& o) { return t < o.stamp_s; });
  const sensor::OdometryData& b = *it;
  const sensor::OdometryData& a = *(it - 1);
  const double span = b.stamp_s - a.stamp_s;
  const double fraction = span > 0 ? (stamp_s - a.stamp_s) / span : 1.0;
  *T_odom_base = common::Interpolate(a.pose, b.pose, fraction);
  return true;
}

common::Rigid2d PoseExtrapolator2D::ExtrapolatePose(double stamp_s) const {
  const TimedPose& last = poses_.back();
  if (stamp_s <= last.stamp_s) return last.pose;
  common::Rigid2d odom_then, odom_now;
  if (InterpolateOdometry(last.stamp_s, &odom_then) && InterpolateOdometry(stamp_s, &odom_now)) {
    return last.pose * (odom_then.inverse() * odom_now);
  }
  return ExtrapolatePoseWithoutOdometry(stamp_s);
}

common::Rigid2d PoseExtrapolator2D::ExtrapolatePoseWithoutOdometry(double stamp_s) const {
  const TimedPose& last = poses_.back();
  if (stamp_s <= last.stamp_s) return last.pose;
  const double dt = stamp_s - last.stamp_s;
  double yaw_rate = angular_velocity_radps_;
  if (!imu_.empty() && imu_.back().stamp_s > last.stamp_s - kOdometryHistoryMarginS) {
    yaw_rate = imu_.back().angular_velocity_radps.z();
  }
  return common::Rigid2d(last.pose.translation() + dt * linear_velocity_mps_,
                         last.pose.angle_rad() + dt * yaw_rate);
}

}  // namespace mapping
}  // namespace fusemap
