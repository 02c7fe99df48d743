#include "fusemap/eval/trajectory.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace fusemap {
namespace eval {
namespace {

// Index of the first sample with stamp >= stamp_s (trajectory.size() if none).
size_t LowerBound(const Trajectory& trajectory, double stamp_s) {
  const auto it = std::lower_bound(
      trajectory.begin(), trajectory.end(), stamp_s,
      [](const TimedPose3d& sample, double stamp) { return sample.stamp_s < stamp; });
  return static_cast<size_t>(it - trajectory.begin());
}

// Index of the sample nearest to stamp_s; trajectory must not be empty.
size_t Nearest(const Trajectory& trajectory, double stamp_s) {
  const size_t upper = LowerBound(trajectory, stamp_s);
  if (upper == 0) return 0;
  if (upper == trajectory.size()) return upper - 1;
  const double d_upper = trajectory[upper].stamp_s - stamp_s;
  const double d_lower = stamp_s - trajectory[upper - 1].stamp_s;
  return d_lower <= d_upper ? upper - 1 : upper;
}

}  // namespace

bool IsStrictlyIncreasing(const Trajectory& trajectory) {
  for (size_t i = 1; i < trajectory.size(); ++i) {
    if (!(trajectory[i].stamp_s > trajectory[i - 1].stamp_s)) return false;
  }
  return true;
}

bool LookUpPose(const Trajectory& trajectory, double stamp_s, double max_time_gap_s,
                common::Rigid3d* pose) {
  assert(pose != nullptr);
  assert(IsStrictlyIncreasing(trajectory));
  if (trajectory.empty()) return false;
  const size_t nearest = Nearest(trajectory, stamp_s);
  if (std::abs(trajectory[nearest].stamp_s - stamp_s) > max_time_gap_s) return false;
  const size_t upper = LowerBound(trajectory, stamp_s);
  if (upper == 0 || upper == trajectory.size() || trajectory[upper].stamp_s == stamp_s) {
    *pose = trajectory[nearest].pose;
    return true;
  }
  const TimedPose3d& a = trajectory[upper - 1];
  const TimedPose3d& b = trajectory[upper];
  const double fraction = (stamp_s - a.stamp_s) / (b.stamp_s - a.stamp_s);
  *pose = common::Interpolate(a.pose, b.pose, fraction);
  return true;
}

std::vector<PosePair> AssociateByTime(const Trajectory& gt, const Trajectory& est,
                                      double max_time_diff_s) {
  assert(IsStrictlyIncreasing(gt));
  std::vector<PosePair> pairs;
  if (gt.empty()) return pairs;
  // Each estimated pose claims its nearest ground-truth pose; a ground-truth pose claimed
  // several times goes to the closest claimant, so the association is one-to-one and a dense
  // estimate does not weight parts of a sparse ground truth several times.
  constexpr size_t kNone = static_cast<size_t>(-1);
  std::vector<size_t> best_est(gt.size(), kNone);
  for (size_t e = 0; e < est.size(); ++e) {
    const size_t g = Nearest(gt, est[e].stamp_s);
    const double diff = std::abs(gt[g].stamp_s - est[e].stamp_s);
    if (diff > max_time_diff_s) continue;
    if (best_est[g] == kNone || diff < std::abs(gt[g].stamp_s - est[best_est[g]].stamp_s)) {
      best_est[g] = e;
    }
  }
  for (size_t g = 0; g < gt.size(); ++g) {
    if (best_est[g] == kNone) continue;
    const TimedPose3d& e = est[best_est[g]];
    pairs.push_back(PosePair{e.stamp_s, gt[g].pose, e.pose});
  }
  return pairs;
}

}  // namespace eval
}  // namespace fusemap
