#ifndef FUSEMAP_EVAL_RELATION_ERROR_H_
#define FUSEMAP_EVAL_RELATION_ERROR_H_

#include <vector>

#include "fusemap/common/rigid_transform.h"
#include "fusemap/eval/error_statistics.h"
#include "fusemap/eval/trajectory.h"

namespace fusemap {
namespace eval {

// A ground-truth relation of Kümmerle et al. (2009), "On measuring the accuracy of SLAM
// algorithms": the true motion from the robot pose at t1_s to the pose at t2_s, expressed in
// the frame of the pose at t1_s.
struct Relation {
  double t1_s = 0.0;
  double t2_s = 0.0;
  common::Rigid2d T_1_2;
};

// The relation metric: for each relation, E = T_1_2_true^-1 * T_1_2_est (est ⊖ true, eq. 2 of
// the paper); translational error |E.t| in metres, rotational |E.angle| in degrees. The
// "squared" statistics summarise the squared errors (m^2, deg^2) as the paper also reports.
struct RelationError {
  int count_used = 0;
  int count_skipped = 0;  // No estimated pose within the time gap of t1 or t2.
  ErrorStatistics trans_m;
  ErrorStatistics rot_deg;
  ErrorStatistics trans_sq_m2;
  ErrorStatistics rot_sq_deg2;
};

constexpr double kDefaultRelationMaxTimeGapS = 0.05;

// Estimated poses are looked up with LookUpPose() (interpolated between neighbours, at most
// max_time_gap_s from a sample) and projected to the plane (x, y, yaw).
RelationError EvaluateRelations(const Trajectory& est, const std::vector<Relation>& relations,
                                double max_time_gap_s = kDefaultRelationMaxTimeGapS);

}  // namespace eval
}  // namespace fusemap

#endif  // FUSEMAP_EVAL_RELATION_ERROR_H_
