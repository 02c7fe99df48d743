#include "fusemap/visual_loop/keyframe_selector.h"

#include <cmath>

namespace fusemap {
namespace visual_loop {

bool KeyframeSelectorOptions::IsValid(std::string* error) const {
  if (!(min_translation_m > 0.0) || !(min_rotation_rad > 0.0) || !(max_interval_s > 0.0) ||
      !(min_interval_s >= 0.0) || min_interval_s > max_interval_s) {
    *error = "keyframe selector: thresholds must be positive and min_interval_s <= max_interval_s";
    return false;
  }
  return true;
}

bool KeyframeSelector::Select(double stamp_s, const common::Rigid2d& T_local_tracking) {
  if (last_stamp_s_) {
    const double dt = stamp_s - *last_stamp_s_;
    if (dt < options_.min_interval_s) return false;
    const common::Rigid2d motion = last_T_local_tracking_.inverse() * T_local_tracking;
    const bool moved = motion.translation().norm() >= options_.min_translation_m ||
                       std::abs(motion.angle_rad()) >= options_.min_rotation_rad;
    if (!moved && dt < options_.max_interval_s) return false;
  }
  last_stamp_s_ = stamp_s;
  last_T_local_tracking_ = T_local_tracking;
  return true;
}

}  // namespace visual_loop
}  // namespace fusemap
