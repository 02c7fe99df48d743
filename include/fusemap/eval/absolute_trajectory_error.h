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
};

// trans_m.count == 0 when no pose could be associated.
AteResult ComputeAte(const Trajectory& gt, const Trajectory& est, const AteOptions& options);

}  // namespace eval
}  // namespace fusemap

#endif  // FUSEMAP_EVAL_ABSOLUTE_TRAJECTORY_ERROR_H_
