#include "fusemap/eval/relative_pose_error.h"

#include <algorithm>
#include <cmath>

#include "fusemap/common/math.h"

namespace fusemap {
namespace eval {
namespace {

// Angle in [0, pi] of the rotation q represents; atan2 stays accurate near zero, where
// acos(w) loses half the digits.
double RotationAngleRad(const Eigen::Quaterniond& q) {
  return 2.0 * std::atan2(q.vec().norm(), std::abs(q.w()));
}

}  // namespace

void RpeOptions::Check(common::OptionChecker* check) const {
  check->Require(delta > 0.0 && std::isfinite(delta), "delta", "must be finite and > 0");
  check->Require(max_time_diff_s >= 0.0 && std::isfinite(max_time_diff_s), "max_time_diff_s",
                 "must be finite and >= 0");
}

bool RpeOptions::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

RpeOptions ParseRpeOptions(common::ConfigReader& reader) {
  RpeOptions options;
  reader.Get("delta", &options.delta);
  reader.Get("max_time_diff_s", &options.max_time_diff_s);
  std::string unit = options.delta_unit == DeltaUnit::kMetres ? "m" : "s";
  reader.Get("delta_unit", &unit);
  if (unit == "m") {
    options.delta_unit = DeltaUnit::kMetres;
  } else if (unit == "s") {
    options.delta_unit = DeltaUnit::kSeconds;
  } else {
    reader.AddError("delta_unit", "must be \"m\" or \"s\", got \"" + unit + "\"");
  }
  reader.CheckOptions(options);
  return options;
}

RpeResult ComputeRpe(const Trajectory& gt, const Trajectory& est, const RpeOptions& options) {
  RpeResult result;
  const std::vector<PosePair> pairs = AssociateByTime(gt, est, options.max_time_diff_s);
  if (pairs.size() < 2) return result;

  std::vector<double> index(pairs.size(), 0.0);
  for (size_t k = 0; k < pairs.size(); ++k) {
    if (options.delta_unit == DeltaUnit::kSeconds) {
      index[k] = pairs[k].stamp_s;
    } else if (k > 0) {
      index[k] = index[k - 1] + (pairs[k].gt.translation() - pairs[k - 1].gt.translation()).norm();
    }
  }

  std::vector<double> trans_m, rot_deg;
  for (size_t i = 0; i + 1 < pairs.size(); ++i) {
    const double target = index[i] + options.delta;
    if (target > index.back()) break;
    size_t j =
        static_cast<size_t>(std::lower_bound(index.begin(), index.end(), target) - index.begin());
    if (j > i + 1 && target - index[j - 1] < index[j] - target) --j;
    const common::Rigid3d gt_motion = pairs[i].gt.inverse() * pairs[j].gt;
    const common::Rigid3d est_motion = pairs[i].est.inverse() * pairs[j].est;
    const common::Rigid3d error = gt_motion.inverse() * est_motion;
    trans_m.push_back(error.translation().norm());
    rot_deg.push_back(common::RadToDeg(RotationAngleRad(error.rotation())));
  }
  result.trans_m = ComputeErrorStatistics(std::move(trans_m));
  result.rot_deg = ComputeErrorStatistics(std::move(rot_deg));
  return result;
}

}  // namespace eval
}  // namespace fusemap
