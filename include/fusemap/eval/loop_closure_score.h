#ifndef FUSEMAP_EVAL_LOOP_CLOSURE_SCORE_H_
#define FUSEMAP_EVAL_LOOP_CLOSURE_SCORE_H_

#include <map>
#include <string>
#include <vector>

#include "fusemap/common/rigid_transform.h"
#include "fusemap/eval/trajectory.h"

namespace fusemap {
namespace eval {

// How far the estimate's motion from its first to its last pose is from the true motion
// between the same stamps: a loop that did not close shows here whatever the alignment.
struct StartEndError {
  double translation_m = 0.0;
  double rotation_deg = 0.0;
};
// False (and *error) if either trajectory is empty or gt has no pose within max_time_gap_s of
// the estimate's first or last stamp.
bool ComputeStartEndError(const Trajectory& gt, const Trajectory& est, double max_time_gap_s,
                          StartEndError* result, std::string* error);

// One line of DIR/loops.tsv: node in submap, what measured it and what was decided.
struct LoopRecord {
  int node = 0;
  int submap = 0;
  std::string source;
  double laser_score = 0.0;
  int visual_inliers = 0;
  std::string decision;
  common::Rigid2d T_submap_node;
  // Node frame; zero when the loop measured every way (loops.tsv unmeasured_x, unmeasured_y),
  // and the turn per metre along it that it did not measure either (unmeasured_turn_rad_per_m).
  Eigen::Vector2d unmeasured_direction = Eigen::Vector2d::Zero();
  double unmeasured_turn_rad_per_m = 0.0;
};

// Where a submap's frame is: its final map pose and the node whose insertion started it
// (DIR/submaps.tsv). The submap frame is tied to that node by local SLAM, so the node's true
// pose gives the submap frame's true pose.
struct SubmapAnchor {
  int submap = 0;
  int first_node = 0;
  common::Rigid2d T_map_submap;
};

struct LoopScoreOptions {
  double max_translation_error_m = 0.3;  // issue 17: wrong beyond 0.3 m or 3 deg
  double max_rotation_error_deg = 3.0;
  double max_time_gap_s = 0.05;  // node stamp to ground truth
};

struct ScoredLoop {
  LoopRecord loop;
  bool scored = false;  // false: node, submap or truth missing
  bool accepted = false;
  double translation_error_m = 0.0;
  double rotation_error_deg = 0.0;
  bool wrong = false;
};

struct LoopScore {
  std::vector<ScoredLoop> loops;
  std::map<std::string, int> by_decision;
  std::map<std::string, int> wrong_by_decision;  // scored loops off the truth, by decision
  int accepted = 0;
  int wrong_accepted = 0;
  int wrong_rejected = 0;  // wrong measurements the decision kept out of the graph
  int unscored = 0;
  // Scored loops that held the node across a corridor only: their error along it not counted.
  int held_across_only = 0;
};

// A loop counts as accepted unless its decision says it was rejected ("…rejected").
bool IsAcceptedDecision(const std::string& decision);

// The implied relative pose of each loop against the truth (across the corridor only for a
// loop with an unmeasured direction): the true T_submap_node is
// T_submap_anchor * T_world_anchor^-1 * T_world_node with T_world_* from gt at the nodes'
// stamps and T_submap_anchor from the estimate (local, accurate even when the loop is not).
// `nodes` are the estimated node poses in index order (DIR/nodes.tum).
LoopScore ScoreLoops(const std::vector<LoopRecord>& loops, const std::vector<SubmapAnchor>& submaps,
                     const Trajectory& nodes, const Trajectory& gt, const LoopScoreOptions& options);

}  // namespace eval
}  // namespace fusemap

#endif  // FUSEMAP_EVAL_LOOP_CLOSURE_SCORE_H_
