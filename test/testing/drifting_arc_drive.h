#ifndef FUSEMAP_TEST_TESTING_DRIFTING_ARC_DRIVE_H_
#define FUSEMAP_TEST_TESTING_DRIFTING_ARC_DRIVE_H_

// Stands in for local SLAM on the synthetic room's arc (ArcPose) with a known drift: every
// step's estimated motion has 1 % too much translation and 0.1 deg too much yaw, and scans go
// into submaps (10 range data each) at the drifted poses, so submaps and nodes are
// consistently wrong, as they are after real local SLAM. Header-only and test-only.

#include <memory>
#include <vector>

#include "fusemap/common/math.h"
#include "fusemap/mapping/submap_2d.h"
#include "fusemap/sensor/range_data_builder.h"
#include "fusemap/sensor/voxel_filter.h"
#include "testing/synthetic_room.h"

namespace fusemap {
namespace test_world {

class DriftingArcDrive {
 public:
  // What local SLAM hands the pose graph for one scan.
  struct Step {
    int index = 0;
    common::Rigid2d T_true;
    common::Rigid2d T_local_node;
    sensor::PointCloud2d filtered_cloud;
    std::vector<std::shared_ptr<const mapping::Submap2D>> insertion_submaps;
  };

  explicit DriftingArcDrive(double step_m) : step_m_(step_m), walls_(Room()) {
    mapping::SubmapsOptions submap_options;
    submap_options.num_range_data = 10;
    active_ = std::make_unique<mapping::ActiveSubmaps2D>(submap_options);
    filter_.max_length_m = 0.9f;
    filter_.min_num_points = 100;
  }

  Step Next() {
    Step step;
    step.index = next_++;
    step.T_true = ArcPose(step.index, step_m_);
    if (step.index > 0) {
      const common::Rigid2d delta = ArcPose(step.index - 1, step_m_).inverse() * step.T_true;
      T_local_node_ = T_local_node_ * common::Rigid2d(1.01 * delta.translation(),
                                                      delta.angle_rad() + common::DegToRad(0.1));
    }
    step.T_local_node = T_local_node_;
    const sensor::RangeData data = SimulateRangeData(walls_, step.T_true);
    step.insertion_submaps =
        active_->InsertRangeData(sensor::TransformRangeData(data, T_local_node_));
    if (step.index == 0) first_submap_ = step.insertion_submaps.front();
    step.filtered_cloud = sensor::AdaptiveVoxelFilter(data.returns, filter_);
    return step;
  }

  int next_index() const { return next_; }
  // The true pose of step `index` in the first submap's frame (local SLAM barely drifted
  // while it was built, so its local pose is close to the truth).
  common::Rigid2d TrueInFirstSubmap(int index) const {
    return first_submap_->T_local_submap().inverse() * ArcPose(index, step_m_);
  }

 private:
  const double step_m_;
  const std::vector<Segment> walls_;
  std::unique_ptr<mapping::ActiveSubmaps2D> active_;
  sensor::AdaptiveVoxelFilterOptions filter_;
  common::Rigid2d T_local_node_ = ArcPose(0, step_m_);
  std::shared_ptr<const mapping::Submap2D> first_submap_;
  int next_ = 0;
};

}  // namespace test_world
}  // namespace fusemap

#endif  // FUSEMAP_TEST_TESTING_DRIFTING_ARC_DRIVE_H_
