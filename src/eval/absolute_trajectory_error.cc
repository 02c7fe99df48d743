#include "fusemap/eval/absolute_trajectory_error.h"

#include <Eigen/Geometry>
#include <cmath>

namespace fusemap {
namespace eval {

void AteOptions::Check(common::OptionChecker* check) const {
  check->Require(max_time_diff_s >= 0.0 && std::isfinite(max_time_diff_s), "max_time_diff_s",
                 "must be finite and >= 0");
  check->Require(interpolate_max_gap_s >= 0.0 && std::isfinite(interpolate_max_gap_s),
                 "interpolate_max_gap_s", "must be finite and >= 0");
  check->Require(!scale || (align && planar), "scale", "needs a planar alignment (--se2)");
}

bool AteOptions::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

AteOptions ParseAteOptions(common::ConfigReader& reader) {
  AteOptions options;
  reader.Get("max_time_diff_s", &options.max_time_diff_s);
  reader.Get("align", &options.align);
  reader.Get("planar", &options.planar);
  reader.Get("interpolate_max_gap_s", &options.interpolate_max_gap_s);
  reader.Get("scale", &options.scale);
  reader.CheckOptions(options);
  return options;
}

namespace {

std::vector<PosePair> InterpolateAtGtStamps(const Trajectory& gt, const Trajectory& est,
                                            double max_gap_s) {
  std::vector<PosePair> pairs;
  for (const TimedPose3d& g : gt) {
    common::Rigid3d pose;
    if (LookUpPose(est, g.stamp_s, max_gap_s, &pose)) pairs.push_back({g.stamp_s, g.pose, pose});
  }
  return pairs;
}

// Least-squares x, y, yaw (and with `scale`, a uniform scale) of gt = T * est (Umeyama 1991
// in two dimensions), lifted to 3D; the scale goes to *scale_out.
common::Rigid3d AlignPlanar(const Eigen::Matrix3Xd& p_est, const Eigen::Matrix3Xd& p_gt, bool scale,
                            double* scale_out) {
  const Eigen::Matrix3d T = Eigen::umeyama(Eigen::Matrix2Xd(p_est.topRows<2>()),
                                           Eigen::Matrix2Xd(p_gt.topRows<2>()), scale);
  // The top-left block is scale * rotation.
  *scale_out = scale ? Eigen::Vector2d(T(0, 0), T(1, 0)).norm() : 1.0;
  const double yaw_rad = std::atan2(T(1, 0), T(0, 0));
  return common::Rigid3d(Eigen::Vector3d(T(0, 2), T(1, 2), 0.0),
                         Eigen::Quaterniond(Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ())));
}

}  // namespace

AteResult ComputeAte(const Trajectory& gt, const Trajectory& est, const AteOptions& options) {
  AteResult result;
  const std::vector<PosePair> pairs =
      options.interpolate_max_gap_s > 0.0
          ? InterpolateAtGtStamps(gt, est, options.interpolate_max_gap_s)
          : AssociateByTime(gt, est, options.max_time_diff_s);
  if (pairs.empty()) return result;

  Eigen::Matrix3Xd p_est(3, pairs.size());
  Eigen::Matrix3Xd p_gt(3, pairs.size());
  for (size_t i = 0; i < pairs.size(); ++i) {
    p_est.col(i) = pairs[i].est.translation();
    p_gt.col(i) = pairs[i].gt.translation();
  }
  result.unaligned_rmse_m = std::sqrt((p_gt - p_est).colwise().squaredNorm().mean());

  // Umeyama needs at least two points to define anything; with one, alignment would zero it.
  if (options.align && options.planar && pairs.size() >= 2) {
    result.T_gt_est = AlignPlanar(p_est, p_gt, options.scale, &result.scale);
  } else if (options.align && pairs.size() >= 2) {
    const Eigen::Matrix4d T = Eigen::umeyama(p_est, p_gt, /*with_scaling=*/false);
    result.T_gt_est = common::Rigid3d(T.block<3, 1>(0, 3),
                                      Eigen::Quaterniond(Eigen::Matrix3d(T.block<3, 3>(0, 0))));
  }
  std::vector<double> errors(pairs.size());
  for (size_t i = 0; i < pairs.size(); ++i) {
    errors[i] =
        (p_gt.col(i) - result.T_gt_est * Eigen::Vector3d(result.scale * p_est.col(i))).norm();
  }
  result.trans_m = ComputeErrorStatistics(std::move(errors));
  return result;
}

}  // namespace eval
}  // namespace fusemap
