#include "fusemap/eval/relation_error.h"

#include <cmath>

#include "fusemap/common/math.h"

namespace fusemap {
namespace eval {

RelationError EvaluateRelations(const Trajectory& est, const std::vector<Relation>& relations,
                                double max_time_gap_s) {
  RelationError result;
  std::vector<double> trans_m, rot_deg, trans_sq, rot_sq;
  for (const Relation& relation : relations) {
    common::Rigid3d T_world_1, T_world_2;
    if (!LookUpPose(est, relation.t1_s, max_time_gap_s, &T_world_1) ||
        !LookUpPose(est, relation.t2_s, max_time_gap_s, &T_world_2)) {
      ++result.count_skipped;
      continue;
    }
    const common::Rigid2d T_1_2_est = T_world_1.ToRigid2d().inverse() * T_world_2.ToRigid2d();
    const common::Rigid2d error = relation.T_1_2.inverse() * T_1_2_est;
    const double e_trans = error.translation().norm();
    const double e_rot = std::abs(common::RadToDeg(error.angle_rad()));
    trans_m.push_back(e_trans);
    rot_deg.push_back(e_rot);
    trans_sq.push_back(e_trans * e_trans);
    rot_sq.push_back(e_rot * e_rot);
  }
  result.count_used = static_cast<int>(trans_m.size());
  result.trans_m = ComputeErrorStatistics(std::move(trans_m));
  result.rot_deg = ComputeErrorStatistics(std::move(rot_deg));
  result.trans_sq_m2 = ComputeErrorStatistics(std::move(trans_sq));
  result.rot_sq_deg2 = ComputeErrorStatistics(std::move(rot_sq));
  return result;
}

}  // namespace eval
}  // namespace fusemap
