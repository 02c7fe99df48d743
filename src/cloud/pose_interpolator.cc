#include "fusemap/cloud/pose_interpolator.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <iterator>
#include <limits>

namespace fusemap {
namespace cloud {

void PoseInterpolatorOptions::Check(common::OptionChecker* check) const {
  check->Require(max_history_s > 0.0, "max_history_s", "must be > 0");
  check->Require(max_gap_s > 0.0, "max_gap_s", "must be > 0");
  check->Require(hold_s >= 0.0, "hold_s", "must be >= 0");
}

bool PoseInterpolatorOptions::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

PoseInterpolatorOptions ParsePoseInterpolatorOptions(common::ConfigReader& reader) {
  PoseInterpolatorOptions options;
  reader.Get("max_history_s", &options.max_history_s);
  reader.Get("max_gap_s", &options.max_gap_s);
  reader.Get("hold_s", &options.hold_s);
  reader.CheckOptions(options);
  return options;
}

PoseInterpolator::PoseInterpolator(const PoseInterpolatorOptions& options) : options_(options) {
  assert(options.IsValid(nullptr));
}

double PoseInterpolator::oldest_stamp_s() const {
  return poses_.empty() ? std::numeric_limits<double>::quiet_NaN() : poses_.front().stamp_s;
}

double PoseInterpolator::newest_stamp_s() const {
  return poses_.empty() ? std::numeric_limits<double>::quiet_NaN() : poses_.back().stamp_s;
}

bool PoseInterpolator::AddPose(double stamp_s, const common::Rigid2d& T_local_tracking) {
  if (!std::isfinite(stamp_s) || (!poses_.empty() && stamp_s <= poses_.back().stamp_s)) {
    ++num_rejected_poses_;
    return false;
  }
  poses_.push_back(TimedPose{stamp_s, T_local_tracking});
  const double horizon_s = stamp_s - options_.max_history_s;
  while (poses_.front().stamp_s < horizon_s) poses_.pop_front();
  return true;
}

PoseInterpolator::Result PoseInterpolator::Drop(int64_t* counter) {
  ++*counter;
  return Result();
}

PoseInterpolator::Result PoseInterpolator::Lookup(double stamp_s, double now_s) {
  if (poses_.empty() || stamp_s > poses_.back().stamp_s) {
    if (now_s - stamp_s <= options_.hold_s) return Result{Status::kWait, {}};
    return Drop(&num_dropped_timeout_);
  }
  if (stamp_s < poses_.front().stamp_s) return Drop(&num_dropped_too_old_);

  // First sample not earlier than stamp_s; exists because stamp_s <= newest stamp.
  const auto after = std::lower_bound(
      poses_.begin(), poses_.end(), stamp_s,
      [](const TimedPose& pose, double stamp) { return pose.stamp_s < stamp; });
  if (after->stamp_s == stamp_s) return Result{Status::kReady, after->T_local_tracking};
  const auto before = std::prev(after);
  const double gap_s = after->stamp_s - before->stamp_s;
  if (gap_s > options_.max_gap_s) return Drop(&num_dropped_gap_);
  const double fraction = (stamp_s - before->stamp_s) / gap_s;
  return Result{Status::kReady, common::Interpolate(before->T_local_tracking, after->T_local_tracking, fraction)};
}

}  // namespace cloud
}  // namespace fusemap
