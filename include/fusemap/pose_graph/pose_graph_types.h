#ifndef FUSEMAP_POSE_GRAPH_POSE_GRAPH_TYPES_H_
#define FUSEMAP_POSE_GRAPH_POSE_GRAPH_TYPES_H_

#include <Eigen/Core>

#include "fusemap/common/rigid_transform.h"

namespace fusemap {
namespace pose_graph {

// The graph model of Cartographer-style global SLAM (Hess et al. 2016 Sec. IV): submaps and
// nodes (scans inserted by local SLAM) with poses in the map frame, tied by relative poses.
// Submaps and nodes are numbered 0, 1, ... in the order they are added.

// Node `node` observed in submap `submap`: the pose of the node in the submap frame, from local
// SLAM (kIntraSubmap) or from a scan match against a finished submap (kInterSubmap, a loop
// closure). Residual = weights .* (T_submap_node ⊖ T_map_submap^-1 * T_map_node).
// kLoopClosureCandidate: a match waiting for loop-closure verification; not optimised.
struct Constraint2D {
  enum Tag { kIntraSubmap, kInterSubmap, kLoopClosureCandidate };
  // What measured a loop closure: the laser matcher, the visual loop checker (forced or
  // overriding a laser one), or a laser match the camera confirmed. Intra-submap ones: kLaser.
  enum Source { kLaser, kVisual, kBoth };

  int submap = 0;
  int node = 0;
  common::Rigid2d T_submap_node;
  double translation_weight = 1.0;
  double rotation_weight = 1.0;
  Tag tag = kIntraSubmap;
  Source source = kLaser;
  // Loop closures (and candidates): a stable id, PoseGraph2D's handle for them; -1 otherwise.
  int loop_id = -1;
  double laser_score = 0.0;  // the laser matcher's score, laser loop closures only
  // Laser loop closures: how much better the scan fits the submap at the constraint's pose than
  // at the graph's estimate, in standard errors of the per-point gain
  // (mapping::GainInStandardErrors; see ConstraintBuilderOptions2D::min_correction_evidence_z).
  double evidence_z = 0.0;
  // A laser loop closure whose scan holds the match in one direction only (a corridor of plain
  // walls, mapping::ScanInformation2D): the unit vector, in the node's frame, along which it
  // measures nothing. Zero when it measures every way.
  Eigen::Vector2d unmeasured_direction = Eigen::Vector2d::Zero();
  // With it, the turn in rad per metre along unmeasured_direction that it does not measure
  // either (ScanInformation2D::weakest_turn_rad_per_m): a match that slides round a curved wall
  // turns with it, so sliding alone would leave a wrong heading measured.
  double unmeasured_turn_rad_per_m = 0.0;
};

// Odometry or local-SLAM relative motion between two nodes (usually consecutive ones).
struct NodeToNodeConstraint2D {
  int from = 0;
  int to = 0;
  common::Rigid2d T_from_to;
  double translation_weight = 1.0;
  double rotation_weight = 1.0;
  // Along this unit vector (in the measurement's frame) the translation weight is
  // weak_weight_fraction of translation_weight; zero: the full weight every way.
  Eigen::Vector2d weak_direction = Eigen::Vector2d::Zero();
  double weak_weight_fraction = 1.0;
  bool robust = false;  // Huber loss (a measurement that may be wrong)
};

}  // namespace pose_graph
}  // namespace fusemap

#endif  // FUSEMAP_POSE_GRAPH_POSE_GRAPH_TYPES_H_
