#include "fusemap/eval/loop_closure_score.h"

#include <cmath>

#include "fusemap/common/math.h"

namespace fusemap {
namespace eval {
namespace {

common::Rigid2d Planar(const common::Rigid3d& pose) { return pose.ToRigid2d(); }

double WrappedDeg(double angle_rad) {
  return std::abs(std::remainder(angle_rad, 2.0 * common::kPi)) * 180.0 / common::kPi;
}

}  // namespace

bool ComputeStartEndError(const Trajectory& gt, const Trajectory& est, double max_time_gap_s,
                          StartEndError* result, std::string* error) {
  if (gt.empty() || est.empty()) {
    *error = "empty trajectory";
    return false;
  }
  common::Rigid3d gt_first, gt_last;
  if (!LookUpPose(gt, est.front().stamp_s, max_time_gap_s, &gt_first) ||
      !LookUpPose(gt, est.back().stamp_s, max_time_gap_s, &gt_last)) {
    *error = "no ground truth near the estimate's first or last stamp";
    return false;
  }
  const common::Rigid2d true_motion = Planar(gt_first).inverse() * Planar(gt_last);
  const common::Rigid2d est_motion = Planar(est.front().pose).inverse() * Planar(est.back().pose);
  const common::Rigid2d difference = true_motion.inverse() * est_motion;
  result->translation_m = difference.translation().norm();
  result->rotation_deg = WrappedDeg(difference.angle_rad());
  return true;
}

bool IsAcceptedDecision(const std::string& decision) {
  return decision.find("reject") == std::string::npos;
}

LoopScore ScoreLoops(const std::vector<LoopRecord>& loops, const std::vector<SubmapAnchor>& submaps,
                     const Trajectory& nodes, const Trajectory& gt, const LoopScoreOptions& options) {
  std::map<int, const SubmapAnchor*> anchors;
  for (const SubmapAnchor& anchor : submaps) anchors[anchor.submap] = &anchor;
  const int node_count = static_cast<int>(nodes.size());
  auto true_pose = [&](int node, common::Rigid2d* pose) {
    common::Rigid3d pose3;
    if (node < 0 || node >= node_count ||
        !LookUpPose(gt, nodes[node].stamp_s, options.max_time_gap_s, &pose3)) {
      return false;
    }
    *pose = Planar(pose3);
    return true;
  };
  LoopScore score;
  for (const LoopRecord& loop : loops) {
    ScoredLoop scored;
    scored.loop = loop;
    scored.accepted = IsAcceptedDecision(loop.decision);
    ++score.by_decision[loop.decision];
    if (scored.accepted) ++score.accepted;
    const auto anchor = anchors.find(loop.submap);
    common::Rigid2d T_world_node, T_world_anchor;
    if (anchor != anchors.end() && true_pose(loop.node, &T_world_node) &&
        true_pose(anchor->second->first_node, &T_world_anchor)) {
      const common::Rigid2d T_submap_anchor =
          anchor->second->T_map_submap.inverse() * Planar(nodes[anchor->second->first_node].pose);
      const common::Rigid2d T_submap_node_true =
          T_submap_anchor * T_world_anchor.inverse() * T_world_node;
      const common::Rigid2d difference = T_submap_node_true.inverse() * loop.T_submap_node;
      scored.scored = true;
      // A loop held across a corridor only asserts nothing along it (its translation there is
      // the graph's estimate), nor the turn that goes with sliding round a curved one: only the
      // error across counts, with the heading it has at the true place along the corridor.
      Eigen::Vector2d error_m = difference.translation();
      double error_rad = difference.angle_rad();
      const double unmeasured_norm = loop.unmeasured_direction.norm();
      if (unmeasured_norm > 0.0) {
        const Eigen::Vector2d along = loop.unmeasured_direction / unmeasured_norm;
        const double along_m = error_m.dot(along);
        error_m -= along_m * along;
        error_rad -= along_m * loop.unmeasured_turn_rad_per_m;
        ++score.held_across_only;
      }
      scored.translation_error_m = error_m.norm();
      scored.rotation_error_deg = WrappedDeg(error_rad);
      scored.wrong = scored.translation_error_m > options.max_translation_error_m ||
                     scored.rotation_error_deg > options.max_rotation_error_deg;
      if (scored.wrong) ++score.wrong_by_decision[loop.decision];
      if (scored.wrong && scored.accepted) ++score.wrong_accepted;
      if (scored.wrong && !scored.accepted) ++score.wrong_rejected;
    } else {
      ++score.unscored;
    }
    score.loops.push_back(scored);
  }
  return score;
}

}  // namespace eval
}  // namespace fusemap
