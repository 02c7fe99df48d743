#include "fusemap/pose_graph/loop_closure_verifier_2d.h"

#include <cassert>
#include <cmath>
#include <cstdlib>

#include "fusemap/common/math.h"

namespace fusemap {
namespace pose_graph {

void LoopClosureVerificationOptions2D::Check(common::OptionChecker* check) const {
  check->Require(min_agreeing_closures >= 0, "min_agreeing_closures", "must be >= 0");
  check->Require(max_node_gap >= 1, "max_node_gap", "must be >= 1");
  check->Require(max_translation_error_m > 0.0, "max_translation_error_m", "must be > 0");
  check->Require(max_rotation_error_rad > 0.0 && max_rotation_error_rad <= common::kPi,
                 "max_rotation_error_rad", "must be in (0, pi]");
}

bool LoopClosureVerificationOptions2D::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

LoopClosureVerificationOptions2D ParseLoopClosureVerificationOptions2D(
    common::ConfigReader& reader) {
  LoopClosureVerificationOptions2D options;
  reader.Get("min_agreeing_closures", &options.min_agreeing_closures);
  reader.Get("max_node_gap", &options.max_node_gap);
  reader.Get("max_translation_error_m", &options.max_translation_error_m);
  reader.Get("max_rotation_error_rad", &options.max_rotation_error_rad);
  reader.CheckOptions(options);
  return options;
}

bool ClosuresAgree(const ClosureView2D& a, const ClosureView2D& b,
                   const LoopClosureVerificationOptions2D& options) {
  if (a.node == b.node || std::abs(a.node - b.node) > options.max_node_gap) return false;
  const common::Rigid2d T_a_b_matched =
      a.T_submap_node.inverse() * a.T_local_submap.inverse() * b.T_local_submap * b.T_submap_node;
  const common::Rigid2d T_a_b_local = a.T_local_node.inverse() * b.T_local_node;
  const common::Rigid2d error = T_a_b_local.inverse() * T_a_b_matched;
  return error.translation().norm() <= options.max_translation_error_m &&
         std::abs(error.angle_rad()) <= options.max_rotation_error_rad;
}

namespace {

int CountAgreeing(const std::vector<ClosureView2D>& closures, int index,
                  const LoopClosureVerificationOptions2D& options) {
  int count = 0;
  for (int j = 0; j < static_cast<int>(closures.size()); ++j) {
    if (j != index && ClosuresAgree(closures[index], closures[j], options)) ++count;
  }
  return count;
}

}  // namespace

std::vector<int> ClosuresToAccept(const std::vector<ClosureView2D>& closures, int new_index,
                                  const LoopClosureVerificationOptions2D& options) {
  assert(new_index >= 0 && new_index < static_cast<int>(closures.size()));
  std::vector<int> accept;
  const ClosureView2D& added = closures[new_index];
  int agreeing = 0;
  // Only the new closure and those agreeing with it gained a partner.
  for (int j = 0; j < static_cast<int>(closures.size()); ++j) {
    if (j == new_index || !ClosuresAgree(added, closures[j], options)) continue;
    ++agreeing;
    if (!closures[j].accepted &&
        CountAgreeing(closures, j, options) >= options.min_agreeing_closures) {
      accept.push_back(j);
    }
  }
  if (!added.accepted && agreeing >= options.min_agreeing_closures) accept.push_back(new_index);
  return accept;
}

}  // namespace pose_graph
}  // namespace fusemap
