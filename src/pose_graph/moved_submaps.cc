#include "fusemap/pose_graph/moved_submaps.h"

#include <algorithm>
#include <cmath>

#include "fusemap/common/math.h"

namespace fusemap {
namespace pose_graph {

bool SubmapMoved(const common::Rigid2d& before, const common::Rigid2d& after) {
  return (after.translation() - before.translation()).norm() > kSubmapMoveThresholdM ||
         std::abs(common::NormalizeAngle(after.angle_rad() - before.angle_rad())) >
             kSubmapMoveThresholdRad;
}

std::vector<SubmapMove> MovedSubmaps(const std::vector<common::Rigid2d>& T_map_submaps_before,
                                     const std::vector<common::Rigid2d>& T_map_submaps_after) {
  std::vector<SubmapMove> moves;
  const size_t num_common = std::min(T_map_submaps_before.size(), T_map_submaps_after.size());
  for (size_t i = 0; i < num_common; ++i) {
    const common::Rigid2d& before = T_map_submaps_before[i];
    const common::Rigid2d& after = T_map_submaps_after[i];
    if (SubmapMoved(before, after)) moves.push_back({static_cast<int>(i), before, after});
  }
  return moves;
}

}  // namespace pose_graph
}  // namespace fusemap
