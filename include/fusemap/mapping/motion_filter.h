#ifndef FUSEMAP_MAPPING_MOTION_FILTER_H_
#define FUSEMAP_MAPPING_MOTION_FILTER_H_

#include <string>

#include "fusemap/common/config_reader.h"
#include "fusemap/common/rigid_transform.h"

namespace fusemap {
namespace mapping {

struct MotionFilterOptions {
  double max_time_s = 5.0;
  double max_distance_m = 0.2;
  double max_angle_rad = 0.0175;  // 1 degree

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};
MotionFilterOptions ParseMotionFilterOptions(common::ConfigReader& reader);

// Lets a scan through to the map only when the robot moved or enough time passed since the
// last one that got through, so a standing robot does not pile copies of one scan into a submap.
class MotionFilter {
 public:
  explicit MotionFilter(const MotionFilterOptions& options) : options_(options) {}

  // True if this pose is too similar to the last accepted one (and so should be dropped).
  bool IsSimilar(double stamp_s, const common::Rigid2d& pose);

  int num_accepted() const { return num_accepted_; }
  int num_total() const { return num_total_; }

 private:
  MotionFilterOptions options_;
  int num_total_ = 0;
  int num_accepted_ = 0;
  double last_stamp_s_ = 0.0;
  common::Rigid2d last_pose_;
};

}  // namespace mapping
}  // namespace fusemap

#endif  // FUSEMAP_MAPPING_MOTION_FILTER_H_
