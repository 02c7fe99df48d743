#ifndef FUSEMAP_VISUAL_LOOP_KEYFRAME_SELECTOR_H_
#define FUSEMAP_VISUAL_LOOP_KEYFRAME_SELECTOR_H_

#include <optional>
#include <string>

#include "fusemap/common/rigid_transform.h"

namespace fusemap {
namespace visual_loop {

struct KeyframeSelectorOptions {
  double min_translation_m = 0.3;   // a few keyframes per metre at most
  double min_rotation_rad = 0.35;   // ~20 degrees: a turn on the spot still sees new walls
  double max_interval_s = 10.0;     // a standing robot still adds one now and then
  double min_interval_s = 0.2;      // never more often than this, whatever the motion
  bool IsValid(std::string* error) const;
};

// Decides from the robot's (local SLAM) pose and time whether a camera frame becomes a keyframe:
// when it moved or turned enough since the last keyframe, or too much time passed.
class KeyframeSelector {
 public:
  explicit KeyframeSelector(const KeyframeSelectorOptions& options) : options_(options) {}
  // True if the frame should be kept; the selector then remembers it as the last keyframe.
  bool Select(double stamp_s, const common::Rigid2d& T_local_tracking);

 private:
  KeyframeSelectorOptions options_;
  std::optional<double> last_stamp_s_;
  common::Rigid2d last_T_local_tracking_;
};

}  // namespace visual_loop
}  // namespace fusemap

#endif  // FUSEMAP_VISUAL_LOOP_KEYFRAME_SELECTOR_H_
