#include "fusemap/eval/absolute_trajectory_error.h"

#include <Eigen/Geometry>
#include <cmath>

namespace fusemap {
namespace eval {

bool AteOptions::IsValid(std::string* error) const {
  if (!(max_time_diff_s >= 0.0) || !std::isfinite(max_time_diff_s)) {
    *error = "max_time_diff_s must be finite and >= 0";
    return false;
  }
  return true;
}

AteOptions ParseAteOptions(common::ConfigReader& reader) {
  AteOptions options;
  reader.Get("max_time_diff_s", &options.max_time_diff_s);
  reader.Get("align", &options.align);
  std::string error;
  if (!options.IsValid(&error)) reader.AddError("max_time_diff_s", error);
  return options;
}

AteResult ComputeAte(const Trajectory& gt, const Trajectory& est, const AteOptions& options) {
  AteResult result;
  const std::vector<PosePair> pairs = AssociateByTime(gt, est, options.max_time_diff_s);
  if (pairs.empty()) return result;

  Eigen::Matrix3Xd p_est(3, pairs.size());
  Eigen::Matrix3Xd p_gt(3, pairs.size());
  for (size_t i = 0; i < pairs.size(); ++i) {
    p_est.col(i) = pairs[i].est.translation();
    p_gt.col(i) = pairs[i].gt.translation();
  }
  result.unaligned_rmse_m = std::sqrt((p_gt - p_est).colwise().squaredNorm().mean());

  // Umeyama needs at least two points to define anything; with one, alignment would zero it.
  if (options.align && pairs.size() >= 2) {
    const Eigen::Matrix4d T = Eigen::umeyama(p_est, p_gt, /*with_scaling=*/false);
    result.T_gt_est = common::Rigid3d(T.block<3, 1>(0, 3),
                                      Eigen::Quaterniond(Eigen::Matrix3d(T.block<3, 3>(0, 0))));
  }
  std::vector<double> errors(pairs.size());
  for (size_t i = 0; i < pairs.size(); ++i) {
    errors[i] = (p_gt.col(i) - result.T_gt_est * Eigen::Vector3d(p_est.col(i))).norm();
  }
  result.trans_m = ComputeErrorStatistics(std::move(errors));
  return result;
}

}  // namespace eval
}  // namespace fusemap
