#ifndef FUSEMAP_EVAL_ABSOLUTE_TRAJECTORY_ERROR_H_
#define FUSEMAP_EVAL_ABSOLUTE_TRAJECTORY_ERROR_H_

#include <string>

#include "fusemap/common/config_reader.h"
#include "fusemap/common/rigid_transform.h"
#include "fusemap/eval/error_statistics.h"
#include "fusemap/eval/trajectory.h"

namespace fusemap {
namespace eval {

struct AteOptions {
  double max_time_diff_s = 0.02;
  // Rigidly align the estimate to the ground truth (SE(3), no scale) before measuring.
  bool align = true;
  // Align in the plane only (x, y, yaw; SE(2)). For a planar robot an SE(3) fit may turn the
  // plane over (a half turn about an in-plane axis mirrors it) when that fits a poor estimate
  // better; a mirrored map is not a rigid motion of the robot's world.
  bool planar = false;
  // With align and planar: also fit one uniform scale of the estimate (a similarity, Sim(2)),
  // reported in AteResult::scale. How much larger or smaller a map is than the reference is then
  // a number apart from the error that remains (issue 14: our maps came out 0.05-0.9 % larger
  // than GMapping's). Refused without align and planar.
  bool scale = false;
  // 0: each estimated pose is associated with the nearest ground-truth stamp (both sampled at
  // the same instants, like nodes against reference poses). > 0: the estimate is sampled at
  // every ground-truth stamp by interpolation (LookUpPose with this maximum gap), for an
  // estimate sampled elsewhere, like odometry against scan poses.
  double interpolate_max_gap_s = 0.0;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

AteOptions ParseAteOptions(common::ConfigReader& reader);

// Absolute trajectory error of Sturm et al. (2012), "A benchmark for the evaluation of RGB-D
// SLAM systems", Sec. VI-B: position differences of time-associated poses after the
// least-squares rigid alignment of Horn/Umeyama (1991).
struct AteResult {
  ErrorStatistics trans_m;        // After alignment (equal to unaligned if align=false).
  double unaligned_rmse_m = 0.0;  // With T_gt_est = identity.
  common::Rigid3d T_gt_est;       // Applied to estimated positions before differencing.
  // Multiplies estimated positions before T_gt_est (gt = T_gt_est * (scale * est)); 1 unless
  // AteOptions::scale. Below 1: the estimate is larger than the ground truth.
  double scale = 1.0;
};

// trans_m.count == 0 when no pose could be associated.
AteResult ComputeAte(const Trajectory& gt, const Trajectory& est, const AteOptions& options);

}  // namespace eval
}  // namespace fusemap

#endif  // FUSEMAP_EVAL_ABSOLUTE_TRAJECTORY_ERROR_H_
