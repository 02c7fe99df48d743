#ifndef FUSEMAP_POSE_GRAPH_LOOP_CLOSURE_VERIFIER_2D_H_
#define FUSEMAP_POSE_GRAPH_LOOP_CLOSURE_VERIFIER_2D_H_

#include <string>
#include <vector>

#include "fusemap/common/config_reader.h"
#include "fusemap/common/rigid_transform.h"

namespace fusemap {
namespace pose_graph {

struct LoopClosureVerificationOptions2D {
  // A loop closure enters the graph only once at least this many other closures (pending or
  // accepted, of other nodes) agree with it; until then it is a candidate and not optimised.
  // 0 (the default) turns verification off: every match is accepted at once.
  int min_agreeing_closures = 0;
  // Only closures of nodes at most this many nodes apart are compared: local SLAM's relative
  // motion, which the check relies on, is only trustworthy over short stretches.
  int max_node_gap = 30;
  // Two closures agree if the motion between their nodes that they imply differs from local
  // SLAM's by at most this much.
  double max_translation_error_m = 0.3;
  double max_rotation_error_rad = 0.05;

  bool enabled() const { return min_agreeing_closures > 0; }
  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

// Keys: min_agreeing_closures, max_node_gap, max_translation_error_m, max_rotation_error_rad.
LoopClosureVerificationOptions2D ParseLoopClosureVerificationOptions2D(
    common::ConfigReader& reader);

// A loop closure as the verifier sees it: the matched pose of the node in the submap and local
// SLAM's poses of both ends (in its one drifting local frame).
struct ClosureView2D {
  int node = 0;
  int submap = 0;
  common::Rigid2d T_submap_node;
  common::Rigid2d T_local_submap;
  common::Rigid2d T_local_node;
  bool accepted = false;
};

// Pairwise consistency of two closures (as in Olson's single-cluster graph partitioning and
// Mangelson et al. 2018, "Pairwise Consistent Measurement Set Maximization"): the motion from
// node a to node b through the two matches, T_a_b = Z_a^-1 * T_local_sa^-1 * T_local_sb * Z_b,
// must equal local SLAM's T_local_na^-1 * T_local_nb. A wrong match (a corridor matched a door
// further along, a room that looks like another) is rarely repeated by the neighbouring nodes
// with the same error, while right ones agree up to matching noise and short-range drift.
bool ClosuresAgree(const ClosureView2D& a, const ClosureView2D& b,
                   const LoopClosureVerificationOptions2D& options);

// Call after closures[new_index] (a candidate) was added. Returns the indices of the
// candidates, the new one or its partners, that now have min_agreeing_closures agreeing
// closures and should be accepted. Stateless: agreement is recomputed from the list, so the
// result depends only on the set of closures, not on the order they arrived in.
std::vector<int> ClosuresToAccept(const std::vector<ClosureView2D>& closures, int new_index,
                                  const LoopClosureVerificationOptions2D& options);

}  // namespace pose_graph
}  // namespace fusemap

#endif  // FUSEMAP_POSE_GRAPH_LOOP_CLOSURE_VERIFIER_2D_H_
