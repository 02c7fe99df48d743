#include "fusemap/mapping/motion_filter.h"

#include <cmath>

namespace fusemap {
namespace mapping {

void MotionFilterOptions::Check(common::OptionChecker* check) const {
  check->Require(max_time_s >= 0, "max_time_s", "must be >= 0");
  check->Require(max_distance_m >= 0, "max_distance_m", "must be >= 0");
  check->Require(max_angle_rad >= 0, "max_angle_rad", "must be >= 0");
}

bool MotionFilterOptions::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

MotionFilterOptions ParseMotionFilterOptions(common::ConfigReader& reader) {
  MotionFilterOptions options;
  reader.Get("max_time_s", &options.max_time_s);
  reader.Get("max_distance_m", &options.max_distance_m);
  reader.Get("max_angle_rad", &options.max_angle_rad);
  reader.CheckOptions(options);
  return options;
}

bool MotionFilter::IsSimilar(double stamp_s, const common::Rigid2d& pose) {
  ++num_total_;
  if (num_accepted_ > 0 && stamp_s - last_stamp_s_ <= options_.max_time_s &&
      (pose.translation() - last_pose_.translation()).norm() <= options_.max_distance_m &&
      std::abs(common::NormalizeAngle(pose.angle_rad() - last_pose_.angle_rad())) <=
          options_.max_angle_rad) {
    return true;
  }
  ++num_accepted_;
  last_stamp_s_ = stamp_s;
  last_pose_ = pose;
  return false;
}

}  // namespace mapping
}  // namespace fusemap
