#ifndef FUSEMAP_EVAL_TRAJECTORY_H_
#define FUSEMAP_EVAL_TRAJECTORY_H_

#include <vector>

#include "fusemap/common/rigid_transform.h"

namespace fusemap {
namespace eval {

// One pose of a trajectory: T_world_body at stamp_s.
struct TimedPose3d {
  double stamp_s = 0.0;
  common::Rigid3d pose;
};

// Invariant: stamps strictly increasing (io/tum_trajectory enforces it on read).
using Trajectory = std::vector<TimedPose3d>;

// A ground-truth pose and the estimated pose associated with it by time.
struct PosePair {
  double stamp_s = 0.0;  // Stamp of the estimated pose.
  common::Rigid3d gt;
  common::Rigid3d est;
};

bool IsStrictlyIncreasing(const Trajectory& trajectory);

// The pose of `trajectory` at `stamp_s`. Returns false when no sample lies within
// max_time_gap_s of stamp_s. When stamp_s lies between two samples the pose is interpolated
// between them (linear translation, slerp rotation), since a dense odometry-rate trajectory
// makes the neighbours' motion nearly linear and interpolation removes the up-to-half-period
// timing error of picking the nearest sample; at the ends the nearest sample is used as is.
bool LookUpPose(const Trajectory& trajectory, double stamp_s, double max_time_gap_s,
                common::Rigid3d* pose);

// One-to-one association by time (as the TUM RGB-D benchmark tools): each estimated pose is
// matched to the nearest ground-truth pose if their stamps differ by at most max_time_diff_s,
// and each ground-truth pose keeps only its closest match. Pairs are ordered by time.
std::vector<PosePair> AssociateByTime(const Trajectory& gt, const Trajectory& est,
                                      double max_time_diff_s);

}  // namespace eval
}  // namespace fusemap

#endif  // FUSEMAP_EVAL_TRAJECTORY_H_
