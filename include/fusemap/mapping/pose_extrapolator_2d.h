#ifndef FUSEMAP_MAPPING_POSE_EXTRAPOLATOR_2D_H_
#define FUSEMAP_MAPPING_POSE_EXTRAPOLATOR_2D_H_

#include <deque>
#include <vector>

#include "fusemap/common/rigid_transform.h"
#include "fusemap/sensor/sensor_types.h"

namespace fusemap {
namespace mapping {

// Everything a PoseExtrapolator2D holds, as plain values (checkpoints).
struct PoseExtrapolatorState2D {
  struct TimedPose {
    double stamp_s = 0.0;
    common::Rigid2d pose;
  };
  std::vector<TimedPose> poses;  // time-ordered
  std::vector<sensor::OdometryData> odometry;
  std::vector<sensor::ImuData> imu;
  Eigen::Vector2d linear_velocity_mps = Eigen::Vector2d::Zero();
  double angular_velocity_radps = 0.0;
};

// Predicts the robot pose at a future time from the last scan-matched pose. Odometry, when
// present, gives the motion since that pose (interpolated at both ends, not the nearest
// sample); otherwise the velocity estimated from the last two matched poses is held, with the
// IMU's yaw rate replacing the estimated angular velocity when IMU data arrives.
// Invariant: odometry and IMU queues are time-ordered; samples out of order are rejected.
class PoseExtrapolator2D {
 public:
  explicit PoseExtrapolator2D(double pose_queue_duration_s = 0.5);
  // Continues exactly where the extrapolator that exported `state` stopped.
  PoseExtrapolator2D(double pose_queue_duration_s, const PoseExtrapolatorState2D& state);

  PoseExtrapolatorState2D ExportState() const;

  // Scan-matched pose of the tracking frame in the local frame.
  void AddPose(double stamp_s, const common::Rigid2d& T_local_tracking);
  // Returns false (and ignores the sample) if it is older than the last odometry sample.
  bool AddOdometry(const sensor::OdometryData& odometry);
  bool AddImu(const sensor::ImuData& imu);
  // The motion since the last pose is unknown (the time base was reset: a log player looped,
  // the robot may have been carried): odometry and IMU samples so far are dropped, since the
  // next ones need not continue them, and the velocity is zeroed. The next scan is predicted
  // at the last pose, and odometry counts again from the first sample after this.
  void ForgetMotion();

  bool HasPose() const { return !poses_.empty(); }
  double last_pose_stamp_s() const { return poses_.back().stamp_s; }
  // Requires HasPose(). Times before the last pose return that pose.
  common::Rigid2d ExtrapolatePose(double stamp_s) const;
  // The same without odometry: the matched poses' velocity (yaw rate from the IMU if recent).
  // For when odometry predicts something absurd.
  common::Rigid2d ExtrapolatePoseWithoutOdometry(double stamp_s) const;

  // Odometry pose interpolated at `stamp_s`; past the last sample, extrapolated for up to
  // 0.5 s and then held. False without odometry or before the oldest kept sample.
  bool InterpolateOdometry(double stamp_s, common::Rigid2d* T_odom_base) const;

 private:
  struct TimedPose {
    double stamp_s;
    common::Rigid2d pose;
  };
  void TrimQueues();

  double pose_queue_duration_s_;
  std::deque<TimedPose> poses_;
  std::deque<sensor::OdometryData> odometry_;
  std::deque<sensor::ImuData> imu_;
  Eigen::Vector2d linear_velocity_mps_ = Eigen::Vector2d::Zero();  // in the local frame
  double angular_velocity_radps_ = 0.0;
};

}  // namespace mapping
}  // namespace fusemap

#endif  // FUSEMAP_MAPPING_POSE_EXTRAPOLATOR_2D_H_
