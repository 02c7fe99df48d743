// PoseGraph2D's checkpoint support: copying the graph out and rebuilding it.
#include <cassert>
#include <map>

#include "fusemap/pose_graph/pose_graph_2d.h"

namespace fusemap {
namespace pose_graph {

PoseGraphState2D PoseGraph2D::ExportState(
    std::vector<std::shared_ptr<const mapping::Submap2D>>* submaps) const {
  PoseGraphState2D state;
  submaps->clear();
  std::lock_guard<std::mutex> lock(mutex_);
  state.nodes.reserve(nodes_.size());
  for (const auto& node : nodes_) {
    state.nodes.push_back(
        {node.index, node.stamp_s, node.T_local_node, node.cloud, node.inserted_into,
         node.trimmed, node.path_m});
  }
  for (const auto& submap : submaps_) {
    submaps->push_back(submap.submap);
    state.submaps.push_back(
        {submap.finished, submap.trimmed, submap.searchable, submap.sampler_pulses,
         submap.first_path_m, submap.last_path_m});
  }
  state.T_map_nodes = T_map_nodes_;
  state.T_map_submaps = T_map_submaps_;
  state.constraints = constraints_;
  state.node_links = node_links_;
  for (const auto& [id, search] : searches_in_flight_) state.searches_in_flight.push_back(search);
  state.optimization_pending = optimization_running_;
  state.nodes_since_optimization = nodes_since_optimization_;
  state.finished_submaps_at_last_trim = finished_submaps_at_last_trim_;
  state.solve_count = solve_count_;
  state.stats = stats_;
  state.next_loop_id = next_loop_id_;
  return state;
}

void PoseGraph2D::RestoreState(
    const PoseGraphState2D& state,
    const std::vector<std::shared_ptr<const mapping::Submap2D>>& submaps) {
  std::vector<std::function<void()>> tasks;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    assert(nodes_.empty() && submaps_.empty());
    assert(submaps.size() == state.submaps.size());
    assert(state.T_map_nodes.size() == state.nodes.size());
    assert(state.T_map_submaps.size() == state.submaps.size());
    for (const auto& node : state.nodes) {
      nodes_.push_back(
          {node.index, node.stamp_s, node.T_local_node, node.cloud, node.inserted_into,
           node.trimmed, node.path_m});
    }
    for (size_t s = 0; s < submaps.size(); ++s) {
      SubmapData data;
      data.submap = submaps[s];
      data.finished = state.submaps[s].finished;
      data.trimmed = state.submaps[s].trimmed;
      assert(data.trimmed == (submaps[s] == nullptr));
      data.sampler = FixedRatioSampler(options_.constraint_builder.sampling_ratio);
      // The sampler is deterministic in its pulse count, so replaying the pulses restores it.
      for (long i = 0; i < state.submaps[s].sampler_pulses; ++i) data.sampler.Pulse();
      data.sampler_pulses = state.submaps[s].sampler_pulses;
      data.first_path_m = state.submaps[s].first_path_m;
      data.last_path_m = state.submaps[s].last_path_m;
      if (!data.trimmed) submap_index_[submaps[s].get()] = static_cast<int>(s);
      submaps_.push_back(std::move(data));
    }
    T_map_nodes_ = state.T_map_nodes;
    T_map_submaps_ = state.T_map_submaps;
    constraints_ = state.constraints;
    // Which local SLAM steps the links cover, and how their scans pinned them, is recomputed.
    for (const NodeLink2D& link : state.node_links) {
      if (SlotLocked(link.from) < 0 || SlotLocked(link.to) < 0) continue;
      node_links_.push_back(link);
      MarkJudgedStepsLocked(JudgeSteps(UnjudgedStepsLocked(link)));
    }
    // The shortcuts of the drift bound, taken from every accepted loop closure as if all had
    // been solved (the checkpoint does not say which were): at most one optimisation early.
    std::vector<std::pair<int, int>> loops;
    for (const Constraint2D& c : constraints_) {
      if (c.tag == Constraint2D::kInterSubmap) loops.emplace_back(c.node, c.submap);
    }
    SetSolvedClosuresLocked(loops);
    nodes_since_optimization_ = state.nodes_since_optimization;
    finished_submaps_at_last_trim_ = state.finished_submaps_at_last_trim;
    solve_count_ = state.solve_count;
    stats_ = state.stats;
    next_loop_id_ = state.next_loop_id;
    if (options_.optimize_every_n_nodes == 0) return;

    std::map<int, std::vector<PendingSearch2D>> searches_by_submap;
    for (const auto& search : state.searches_in_flight) {
      searches_by_submap[search.submap].push_back(search);
    }
    for (size_t s = 0; s < submaps_.size(); ++s) {
      if (!submaps_[s].finished || submaps_[s].trimmed) continue;
      const std::vector<PendingSearch2D>& searches = searches_by_submap[static_cast<int>(s)];
      if (state.submaps[s].matcher_ready && searches.empty()) {
        // Its precomputation grids are built when a search first needs them.
        submaps_[s].searchable = true;
        continue;
      }
      // A submap whose precomputation had not finished still owes the search of all nodes.
      tasks.push_back(MakeMatcherTask(static_cast<int>(s), submaps_[s].submap,
                                      !state.submaps[s].matcher_ready, searches));
    }
    if (state.optimization_pending) {
      optimization_running_ = true;
      tasks.push_back([this] { RunOptimization(options_.optimization.max_num_iterations); });
    }
  }
  for (auto& task : tasks) executor_->Schedule(std::move(task));
}

}  // namespace pose_graph
}  // namespace fusemap
