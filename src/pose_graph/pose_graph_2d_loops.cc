// PoseGraph2D's loop-constraint API: laser loop closures handed out for a second opinion, loop
// constraints added, replaced or removed from outside, and node links (session::VisualStage).
#include <algorithm>
#include <utility>

#include "fusemap/mapping/scan_matching/scan_information_2d.h"
#include "fusemap/pose_graph/pose_graph_2d.h"

namespace fusemap {
namespace pose_graph {

void PoseGraph2D::ReportLoopClosures() {
  std::lock_guard<std::mutex> lock(mutex_);
  report_loop_closures_ = true;
}

void PoseGraph2D::NoteAcceptedLocked(const Constraint2D& constraint) {
  if (report_loop_closures_ && constraint.source == Constraint2D::kLaser) {
    new_loop_closures_.push_back(constraint.loop_id);
  }
}

Constraint2D* PoseGraph2D::FindLoopLocked(int id) {
  if (id < 0) return nullptr;
  for (Constraint2D& c : constraints_) {
    if (c.loop_id == id) return &c;
  }
  return nullptr;
}

std::vector<LoopClosure2D> PoseGraph2D::TakeNewLoopClosures() {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<LoopClosure2D> closures;
  for (int id : new_loop_closures_) {
    const Constraint2D* c = FindLoopLocked(id);
    if (c == nullptr) continue;  // removed or trimmed meanwhile
    closures.push_back({id, c->node, c->submap, c->T_submap_node, c->laser_score,
                        c->unmeasured_direction, c->unmeasured_turn_rad_per_m});
  }
  new_loop_closures_.clear();
  return closures;
}

int PoseGraph2D::AddLoopConstraint(const ExternalLoopConstraint2D& external) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!PairHeldLocked(external.node, external.submap)) return -1;
  const std::vector<int>& inserted_into = NodeLocked(external.node).inserted_into;
  if (std::find(inserted_into.begin(), inserted_into.end(), external.submap) !=
      inserted_into.end()) {
    return -1;  // local SLAM's own constraint already ties them
  }
  Constraint2D constraint;
  constraint.submap = external.submap;
  constraint.node = external.node;
  constraint.T_submap_node = external.T_submap_node;
  constraint.translation_weight = external.translation_weight;
  constraint.rotation_weight = external.rotation_weight;
  constraint.tag = Constraint2D::kInterSubmap;
  constraint.source = external.source;
  constraint.laser_score = external.laser_score;
  constraint.unmeasured_direction = external.unmeasured_direction;
  constraint.unmeasured_turn_rad_per_m = external.unmeasured_turn_rad_per_m;
  constraint.loop_id = next_loop_id_++;
  constraints_.push_back(constraint);
  NoteAcceptedLocked(constraint);
  return constraint.loop_id;
}

bool PoseGraph2D::ReplaceLoopConstraint(int id, const ExternalLoopConstraint2D& external) {
  std::lock_guard<std::mutex> lock(mutex_);
  Constraint2D* c = FindLoopLocked(id);
  if (c == nullptr) return false;
  c->T_submap_node = external.T_submap_node;
  c->unmeasured_direction = external.unmeasured_direction;
  c->unmeasured_turn_rad_per_m = external.unmeasured_turn_rad_per_m;
  c->translation_weight = external.translation_weight;
  c->rotation_weight = external.rotation_weight;
  c->source = external.source;
  return true;
}

bool PoseGraph2D::SetLoopConstraintSource(int id, Constraint2D::Source source) {
  std::lock_guard<std::mutex> lock(mutex_);
  Constraint2D* c = FindLoopLocked(id);
  if (c == nullptr) return false;
  c->source = source;
  return true;
}

bool PoseGraph2D::RemoveLoopConstraint(int id) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = std::find_if(constraints_.begin(), constraints_.end(),
                               [id](const Constraint2D& c) { return id >= 0 && c.loop_id == id; });
  if (it == constraints_.end()) return false;
  constraints_.erase(it);
  return true;
}

std::vector<Constraint2D> PoseGraph2D::LoopConstraints() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<Constraint2D> loops;
  for (const Constraint2D& c : constraints_) {
    if (c.tag != Constraint2D::kIntraSubmap) loops.push_back(c);
  }
  return loops;
}

PoseGraph2D::StepScans PoseGraph2D::UnjudgedStepsLocked(const NodeLink2D& link) const {
  StepScans steps;
  const int from = SlotLocked(link.from);
  const int to = SlotLocked(link.to);
  if (from < 0 || to < 0) return steps;
  for (int slot = from + 1; slot <= to; ++slot) {
    const NodeData& node = nodes_[slot];
    if (!node.motion_linked && !node.trimmed) steps.emplace_back(node.index, node.cloud);
  }
  return steps;
}

PoseGraph2D::StepDirections PoseGraph2D::JudgeSteps(const StepScans& steps) const {
  const double min_ratio = options_.constraint_builder.min_translation_information_ratio;
  StepDirections directions;
  for (const auto& [node, cloud] : steps) {
    directions.emplace_back(node, mapping::UnpinnedDirection2D(cloud, min_ratio));
  }
  return directions;
}

void PoseGraph2D::MarkJudgedStepsLocked(const StepDirections& directions) {
  for (const auto& [node, direction] : directions) {
    if (NodeGoneLocked(node)) continue;
    NodeData& data = NodeLocked(node);
    data.motion_linked = true;
    data.unmeasured_direction = direction;
  }
}

bool PoseGraph2D::AddNodeLink(const NodeLink2D& link) {
  // The scans of the steps the link covers are judged outside the lock (a fraction of a
  // millisecond each, on the caller's thread): local SLAM adds nodes meanwhile.
  StepScans steps;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!(link.from < link.to) || NodeGoneLocked(link.from) || NodeGoneLocked(link.to)) {
      return false;
    }
    steps = UnjudgedStepsLocked(link);
  }
  const StepDirections directions = JudgeSteps(steps);
  std::lock_guard<std::mutex> lock(mutex_);
  if (NodeGoneLocked(link.from) || NodeGoneLocked(link.to)) return false;
  MarkJudgedStepsLocked(directions);
  node_links_.push_back(link);
  return true;
}

std::vector<NodeLink2D> PoseGraph2D::NodeLinks() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return node_links_;
}

std::optional<double> PoseGraph2D::PathBetween(int node, int submap) const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!PairHeldLocked(node, submap)) return std::nullopt;
  return PathBetweenLocked(node, submap);
}

std::optional<common::Rigid2d> PoseGraph2D::T_submap_node(int submap, int node) const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!PairHeldLocked(node, submap)) return std::nullopt;
  return T_map_submaps_[submap].inverse() * T_map_nodes_[SlotLocked(node)];
}

}  // namespace pose_graph
}  // namespace fusemap
