#include "fusemap/pose_graph/pose_graph_2d.h"

#include <algorithm>
#include <chrono>
#include <iterator>
#include <limits>
#include <utility>

#include "fusemap/common/math.h"
#include "fusemap/pose_graph/sparse_pose_adjustment_2d.h"

namespace fusemap {
namespace pose_graph {
namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

PoseGraphOptions2D::PoseGraphOptions2D() {
  // Cartographer's pose graph uses a much wider Huber scale than a generic SE(2) graph.
  optimization.huber_scale = 1e1;
  // Enough for each optimisation to converge (function_tolerance ends it sooner): the online
  // estimate sets where later closures are searched and whether drift explains them, and at
  // Cartographer's 10 it lagged on a campus' long loops (log benchmark, README Configuration:
  // freiburg-campus against GMapping, median of --threads 2 runs, 0.55 m at 10, 0.49 at 50).
  optimization.max_num_iterations = 50;
}

void PoseGraphOptions2D::Check(common::OptionChecker* check) const {
  check->Require(optimize_every_n_nodes >= 0, "optimize_every_n_nodes", "must be >= 0");
  check->Require(final_optimization_iterations >= 1, "final_optimization_iterations",
                 "must be >= 1");
  check->Require(matcher_translation_weight > 0, "matcher_translation_weight", "must be > 0");
  check->Require(matcher_rotation_weight > 0, "matcher_rotation_weight", "must be > 0");
  check->Require(local_slam_translation_weight >= 0, "local_slam_translation_weight",
                 "must be >= 0");
  check->Require(local_slam_rotation_weight >= 0, "local_slam_rotation_weight", "must be >= 0");
  check->Require(linked_unmeasured_weight_fraction > 0 && linked_unmeasured_weight_fraction <= 1,
                 "linked_unmeasured_weight_fraction", "must be in (0, 1]");
  check->Require(matcher_memory_budget_mb > 0, "matcher_memory_budget_mb", "must be > 0");
  check->Require(max_pending_searches >= 1, "max_pending_searches", "must be >= 1");
  check->Nested("constraint_builder", constraint_builder);
  check->Nested("optimization", optimization);
  check->Nested("overlapping_submaps_trimmer", overlapping_submaps_trimmer);
  check->Nested("loop_closure_verification", loop_closure_verification);
}

bool PoseGraphOptions2D::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

PoseGraphOptions2D ParsePoseGraphOptions2D(common::ConfigReader& reader) {
  PoseGraphOptions2D options;
  reader.Get("optimize_every_n_nodes", &options.optimize_every_n_nodes);
  options.constraint_builder = ParseConstraintBuilderOptions2D(reader.Child("constraint_builder"));
  if (reader.Has("optimization")) {
    options.optimization =
        ParseOptimizationOptions(reader.Child("optimization"), options.optimization);
  }
  reader.Get("matcher_translation_weight", &options.matcher_translation_weight);
  reader.Get("matcher_rotation_weight", &options.matcher_rotation_weight);
  reader.Get("local_slam_translation_weight", &options.local_slam_translation_weight);
  reader.Get("local_slam_rotation_weight", &options.local_slam_rotation_weight);
  reader.Get("linked_unmeasured_weight_fraction", &options.linked_unmeasured_weight_fraction);
  reader.Get("final_optimization_iterations", &options.final_optimization_iterations);
  reader.Get("matcher_memory_budget_mb", &options.matcher_memory_budget_mb);
  reader.Get("max_pending_searches", &options.max_pending_searches);
  if (reader.Has("overlapping_submaps_trimmer")) {
    options.overlapping_submaps_trimmer =
        ParseOverlappingSubmapsTrimmerOptions2D(reader.Child("overlapping_submaps_trimmer"));
  }
  if (reader.Has("loop_closure_verification")) {
    options.loop_closure_verification =
        ParseLoopClosureVerificationOptions2D(reader.Child("loop_closure_verification"));
  }
  reader.CheckOptions(options);
  return options;
}

PoseGraph2D::PoseGraph2D(const PoseGraphOptions2D& options, common::Executor* executor)
    : options_(options), executor_(executor) {}

PoseGraph2D::~PoseGraph2D() { executor_->WaitIdle(); }

int PoseGraph2D::SubmapIndexLocked(const std::shared_ptr<const mapping::Submap2D>& submap,
                                   const common::Rigid2d& T_map_local) {
  const auto it = submap_index_.find(submap.get());
  if (it != submap_index_.end()) return it->second;
  const int index = static_cast<int>(submaps_.size());
  submap_index_[submap.get()] = index;
  SubmapData data;
  data.submap = submap;
  data.sampler = FixedRatioSampler(options_.constraint_builder.sampling_ratio);
  submaps_.push_back(std::move(data));
  T_map_submaps_.push_back(T_map_local * submap->T_local_submap());
  ++stats_.submaps;
  return index;
}

int PoseGraph2D::AddNode(
    double stamp_s, const common::Rigid2d& T_local_node, const sensor::PointCloud2d& filtered_cloud,
    const std::vector<std::shared_ptr<const mapping::Submap2D>>& insertion_submaps) {
  std::vector<std::function<void()>> tasks;
  // Compaction and the optimisation (with the trimming it runs) go ahead of queued searches:
  // behind a backlog of thousands of them (a log played faster than real time) they waited
  // for minutes, and uncompacted and untrimmed submaps piled up (intel played six times: 87
  // submaps held, 43 MB of grids, RSS rising 118 -> 250 MB).
  std::vector<std::function<void()>> upkeep;
  int node;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const common::Rigid2d T_map_local = nodes_.empty()
                                            ? common::Rigid2d::Identity()
                                            : T_map_nodes_.back() * nodes_.back().T_local_node.inverse();
    node = stats_.nodes;
    // The submaps of the previous node that this one is not inserted into have left local
    // SLAM (it keeps a finished submap for one more scan): see below.
    const std::vector<int> previous_inserted_into =
        nodes_.empty() ? std::vector<int>() : nodes_.back().inserted_into;
    // The newest node is never trimmed (it is in the active submap), so nodes_.back() is the
    // previous node.
    const double path_m =
        nodes_.empty() ? 0.0
                       : nodes_.back().path_m + (T_local_node.translation() -
                                                 nodes_.back().T_local_node.translation())
                                                    .norm();
    nodes_.push_back({node, stamp_s, T_local_node, filtered_cloud, {}, false, path_m});
    T_map_nodes_.push_back(T_map_local * T_local_node);
    ++stats_.nodes;

    for (const auto& submap : insertion_submaps) {
      const int s = SubmapIndexLocked(submap, T_map_local);
      nodes_.back().inserted_into.push_back(s);
      SubmapData& submap_data = submaps_[s];
      if (submap_data.first_path_m < 0.0) submap_data.first_path_m = path_m;
      submap_data.last_path_m = path_m;
      Constraint2D constraint;
      constraint.submap = s;
      constraint.node = node;
      constraint.T_submap_node = submap->T_local_submap().inverse() * T_local_node;
      constraint.translation_weight = options_.matcher_translation_weight;
      constraint.rotation_weight = options_.matcher_rotation_weight;
      constraint.tag = Constraint2D::kIntraSubmap;
      constraints_.push_back(constraint);
      ++stats_.intra_constraints;
    }
    // A submap finished by this insertion gets its precomputation grids, then is searched for
    // every earlier node near it.
    for (const auto& submap : insertion_submaps) {
      const int s = submap_index_.at(submap.get());
      if (submap->finished() && !submaps_[s].finished) {
        submaps_[s].finished = true;
        ++stats_.finished_submaps;
        if (options_.optimize_every_n_nodes == 0) continue;
        upkeep.push_back(MakeMatcherTask(s, submap, true, {}));
      }
    }
    // Finished submaps are held for the whole run but read only to precompute, trim and draw:
    // once local SLAM has let go of one, its cells are deflated (lossless; outdoors a submap
    // spans 30 m rays and takes megabytes).
    for (int s : previous_inserted_into) {
      const std::vector<int>& now = nodes_.back().inserted_into;
      const SubmapData& data = submaps_[s];
      if (data.finished && !data.trimmed && std::find(now.begin(), now.end(), s) == now.end()) {
        upkeep.push_back([submap = data.submap] { submap->Compact(); });
      }
    }
    if (options_.optimize_every_n_nodes != 0) {
      // The new node against every finished submap near it.
      for (int s = 0; s < static_cast<int>(submaps_.size()); ++s) {
        if (submaps_[s].searchable) ScheduleSearchLocked(node, s);
      }
      if (++nodes_since_optimization_ >= options_.optimize_every_n_nodes &&
          !optimization_running_) {
        nodes_since_optimization_ = 0;
        optimization_running_ = true;
        upkeep.push_back([this] { RunOptimization(options_.optimization.max_num_iterations); });
      }
      tasks.insert(tasks.end(), pending_tasks_.begin(), pending_tasks_.end());
      pending_tasks_.clear();
      upkeep.insert(upkeep.end(), pending_first_tasks_.begin(), pending_first_tasks_.end());
      pending_first_tasks_.clear();
    }
  }
  // Scheduled outside the lock: an inline executor runs the task right here.
  for (auto& task : tasks) executor_->Schedule(std::move(task));
  for (auto& task : upkeep) executor_->ScheduleFirst(std::move(task));
  return node;
}

namespace {

// Path between the ranges [first_a, last_a] and [first_b, last_b] of the path travelled.
double GapBetween(double first_a, double last_a, double first_b, double last_b) {
  return std::max({0.0, first_b - last_a, first_a - last_b});
}

}  // namespace

double PoseGraph2D::PathBetweenLocked(int node, int submap) const {
  const double path_m = nodes_[SlotLocked(node)].path_m;
  const SubmapData& data = submaps_[submap];
  double best_m = GapBetween(path_m, path_m, data.first_path_m, data.last_path_m);
  for (const SubmapData& via : submaps_) {
    if (via.trimmed || via.solved_closure_paths_m.empty()) continue;
    const double gap_m =
        GapBetween(via.first_path_m, via.last_path_m, data.first_path_m, data.last_path_m);
    if (gap_m >= best_m) continue;
    // The closure whose node is nearest along the chain.
    const std::vector<double>& paths = via.solved_closure_paths_m;
    const auto after = std::lower_bound(paths.begin(), paths.end(), path_m);
    double to_closure_m = std::numeric_limits<double>::infinity();
    if (after != paths.end()) to_closure_m = *after - path_m;
    if (after != paths.begin()) to_closure_m = std::min(to_closure_m, path_m - *(after - 1));
    best_m = std::min(best_m, gap_m + to_closure_m);
  }
  return best_m;
}

void PoseGraph2D::SetSolvedClosuresLocked(const std::vector<std::pair<int, int>>& loops) {
  for (SubmapData& data : submaps_) data.solved_closure_paths_m.clear();
  for (const auto& [node, submap] : loops) {
    const int slot = SlotLocked(node);
    if (slot < 0 || submap < 0 || submap >= static_cast<int>(submaps_.size())) continue;
    submaps_[submap].solved_closure_paths_m.push_back(nodes_[slot].path_m);
  }
  for (SubmapData& data : submaps_) {
    std::sort(data.solved_closure_paths_m.begin(), data.solved_closure_paths_m.end());
  }
}

void PoseGraph2D::ScheduleSearchLocked(int node, int submap) {
  const int slot = SlotLocked(node);
  if (slot < 0 || nodes_[slot].trimmed) return;
  const NodeData& node_data = nodes_[slot];
  SubmapData& submap_data = submaps_[submap];
  for (int s : node_data.inserted_into) {
    if (s == submap) return;
  }
  const common::Rigid2d T_submap_node = T_map_submaps_[submap].inverse() * T_map_nodes_[slot];
  if (T_submap_node.translation().norm() > options_.constraint_builder.max_constraint_distance_m) {
    return;
  }
  ++submap_data.sampler_pulses;
  if (!submap_data.sampler.Pulse()) return;
  if (static_cast<int>(searches_in_flight_.size()) >= options_.max_pending_searches) {
    // The queue is full: this search takes the place of the least valuable ready one, if that
    // is worth less (an older node's).
    ++stats_.searches_skipped;
    if (ready_searches_.empty()) return;
    const auto worst = std::prev(ready_searches_.end());
    if (!(ReadyKey{-node, next_search_id_} < worst->first)) return;
    searches_in_flight_.erase(worst->first.second);
    ready_searches_.erase(worst);
  }
  QueueSearchLocked({node, submap, T_submap_node});
}

void PoseGraph2D::QueueSearchLocked(const PendingSearch2D& search) {
  const std::uint64_t id = next_search_id_++;
  searches_in_flight_[id] = search;
  stats_.max_pending_searches =
      std::max(stats_.max_pending_searches, static_cast<int>(searches_in_flight_.size()));
  SubmapData& data = submaps_[search.submap];
  data.last_used = ++use_clock_;
  if (data.matcher) {
    MakeSearchReadyLocked(id, search);
    return;
  }
  // Released to stay within the memory budget (or not built yet): the search waits for it.
  WaitForMatcherLocked(id, search);
}

void PoseGraph2D::WaitForMatcherLocked(std::uint64_t id, const PendingSearch2D& search) {
  SubmapData& data = submaps_[search.submap];
  data.waiting.emplace_back(id, search);
  if (!data.rebuilding) {
    data.rebuilding = true;
    pending_first_tasks_.push_back(MakeMatcherTask(search.submap, data.submap, false, {}));
  }
}

void PoseGraph2D::MakeSearchReadyLocked(std::uint64_t id, const PendingSearch2D& search) {
  ready_searches_[{-search.node, id}] = search;
  // As many tasks handed out as searches are ready, so every ready search runs; which one each
  // task runs is decided when it starts. Searches dropped meanwhile (trimmed, displaced) leave
  // their tasks to the next ones.
  if (search_tasks_outstanding_ < ready_searches_.size()) {
    ++search_tasks_outstanding_;
    pending_tasks_.push_back([this] { RunBestSearch(); });
  }
}

void PoseGraph2D::RunBestSearch() {
  std::uint64_t id = 0;
  PendingSearch2D search;
  std::shared_ptr<const LoopClosureMatcher2D> matcher;
  std::shared_ptr<const sensor::PointCloud2d> cloud;
  double min_score = 0.0;
  double path_m = 0.0;
  std::vector<std::function<void()>> first_tasks;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    --search_tasks_outstanding_;
    while (!matcher && !ready_searches_.empty()) {
      const auto best = ready_searches_.begin();
      id = best->first.second;
      search = best->second;
      ready_searches_.erase(best);
      matcher = submaps_[search.submap].matcher;
      // Released to stay within the memory budget since it was queued: it waits for the
      // rebuild (holding the released grids here would let them outgrow the budget).
      if (!matcher) WaitForMatcherLocked(id, search);
    }
    if (matcher) {
      cloud = std::make_shared<const sensor::PointCloud2d>(NodeLocked(search.node).cloud);
      min_score = MinScoreForOwnFit(submaps_[search.submap].own_fit, options_.constraint_builder);
      path_m = PathBetweenLocked(search.node, search.submap);
    }
    first_tasks.swap(pending_first_tasks_);
  }
  for (auto& task : first_tasks) executor_->ScheduleFirst(std::move(task));
  if (!matcher) return;
  const auto start = std::chrono::steady_clock::now();
  double score = 0.0;
  std::optional<Constraint2D> constraint =
      matcher->Match(search.T_submap_node, *cloud, min_score, &score, path_m);
  std::lock_guard<std::mutex> lock(mutex_);
  searches_in_flight_.erase(id);
  stats_.loop_closure_search_s += SecondsSince(start);
  ++stats_.loop_closure_searches;
  // The trimmer may have dropped either end while the search ran.
  if (!constraint || submaps_[search.submap].trimmed || NodeGoneLocked(search.node)) return;
  if (!DriftExplainsCorrection(search.T_submap_node, constraint->T_submap_node,
                               PathBetweenLocked(search.node, search.submap),
                               options_.constraint_builder)) {
    ++stats_.loop_closures_beyond_drift;
    return;
  }
  if (!EvidenceSupportsCorrection(search.T_submap_node, constraint->T_submap_node,
                                  constraint->evidence_z, options_.constraint_builder)) {
    ++stats_.loop_closures_ambiguous;
    return;
  }
  constraint->submap = search.submap;
  constraint->node = search.node;
  constraint->laser_score = score;
  if (!constraint->unmeasured_direction.isZero()) ++stats_.loop_closures_degenerate;
  const ConstraintBuilderOptions2D& builder = options_.constraint_builder;
  const bool widened = LoopSearchWindowM(path_m, builder) >
                       builder.fast_correlative_scan_matcher.linear_search_window_m;
  AddLoopClosureLocked(*constraint, widened);
}

double PoseGraph2D::OwnFitLocked(int s, const LoopClosureMatcher2D& matcher) {
  std::vector<double> scores;
  for (const Constraint2D& c : constraints_) {
    if (c.submap != s || c.tag != Constraint2D::kIntraSubmap || NodeGoneLocked(c.node)) continue;
    scores.push_back(matcher.ScoreAt(c.T_submap_node, NodeLocked(c.node).cloud));
  }
  return common::Percentile(std::move(scores), 0.5);  // 0 when empty
}

void PoseGraph2D::InstallMatcherLocked(int s, std::shared_ptr<const LoopClosureMatcher2D> matcher) {
  SubmapData& data = submaps_[s];
  if (data.matcher) matcher_bytes_ -= data.matcher->bytes();
  data.matcher = std::move(matcher);
  matcher_bytes_ += data.matcher->bytes();
  data.last_used = ++use_clock_;
  ++stats_.matcher_builds;
  const size_t budget = static_cast<size_t>(options_.matcher_memory_budget_mb * 1024.0 * 1024.0);
  while (matcher_bytes_ > budget) {
    int oldest = -1;
    for (size_t i = 0; i < submaps_.size(); ++i) {
      if (static_cast<int>(i) == s || !submaps_[i].matcher) continue;
      if (oldest < 0 || submaps_[i].last_used < submaps_[oldest].last_used) {
        oldest = static_cast<int>(i);
      }
    }
    if (oldest < 0) break;  // the new one alone exceeds the budget; it stays
    // Searches already handed to the executor hold their own reference until they finish.
    matcher_bytes_ -= submaps_[oldest].matcher->bytes();
    submaps_[oldest].matcher.reset();
    ++stats_.matcher_evictions;
  }
  if (matcher_bytes_ > stats_.max_matcher_bytes) {
    stats_.max_matcher_bytes = matcher_bytes_;
    stats_.max_matchers = static_cast<int>(std::count_if(
        submaps_.begin(), submaps_.end(), [](const SubmapData& d) { return d.matcher != nullptr; }));
  }
}

void PoseGraph2D::AddLoopClosureLocked(const Constraint2D& constraint, bool needs_agreement) {
  LoopClosureVerificationOptions2D verification = options_.loop_closure_verification;
  constraints_.push_back(constraint);
  constraints_.back().loop_id = next_loop_id_++;
  if (verification.enabled() || needs_agreement) {
    constraints_.back().tag = Constraint2D::kLoopClosureCandidate;
  } else {
    ++stats_.loop_closures_found;
    NoteAcceptedLocked(constraints_.back());
    // Without verification only matches of widened searches wait, for a partner like this one.
    const bool any_waiting = std::any_of(
        constraints_.begin(), constraints_.end(),
        [](const Constraint2D& c) { return c.tag == Constraint2D::kLoopClosureCandidate; });
    if (!any_waiting) return;
  }
  verification.min_agreeing_closures = std::max(verification.min_agreeing_closures, 1);
  // Every match so far, candidate or accepted, in local SLAM's frame, which nothing moves.
  std::vector<ClosureView2D> views;
  std::vector<size_t> constraint_index;
  for (size_t i = 0; i < constraints_.size(); ++i) {
    const Constraint2D& c = constraints_[i];
    if (c.tag == Constraint2D::kIntraSubmap) continue;
    views.push_back({c.node, c.submap, c.T_submap_node, submaps_[c.submap].submap->T_local_submap(),
                     NodeLocked(c.node).T_local_node, c.tag == Constraint2D::kInterSubmap});
    constraint_index.push_back(i);
  }
  for (int v : ClosuresToAccept(views, static_cast<int>(views.size()) - 1, verification)) {
    constraints_[constraint_index[v]].tag = Constraint2D::kInterSubmap;
    ++stats_.loop_closures_found;
    NoteAcceptedLocked(constraints_[constraint_index[v]]);
  }
}

std::function<void()> PoseGraph2D::MakeMatcherTask(
    int s, std::shared_ptr<const mapping::Submap2D> submap, bool search_all_nodes,
    std::vector<PendingSearch2D> searches) {
  return [this, s, submap, search_all_nodes, searches] {
    const auto start = std::chrono::steady_clock::now();
    auto matcher =
        std::make_shared<const LoopClosureMatcher2D>(submap, options_.constraint_builder);
    std::vector<std::function<void()>> tasks, first_tasks;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stats_.precomputation_s += SecondsSince(start);
      SubmapData& data = submaps_[s];
      data.rebuilding = false;
      if (data.trimmed) return;
      InstallMatcherLocked(s, matcher);
      if (data.own_fit == 0.0) data.own_fit = OwnFitLocked(s, *matcher);
      data.searchable = true;
      for (const auto& [id, search] : data.waiting) {
        if (searches_in_flight_.count(id) != 0) MakeSearchReadyLocked(id, search);
      }
      data.waiting.clear();
      for (const auto& search : searches) QueueSearchLocked(search);
      if (search_all_nodes) {
        for (size_t n = 0; n < nodes_.size(); ++n) ScheduleSearchLocked(nodes_[n].index, s);
      }
      tasks.swap(pending_tasks_);
      first_tasks.swap(pending_first_tasks_);
    }
    for (auto& task : tasks) executor_->Schedule(std::move(task));
    for (auto& task : first_tasks) executor_->ScheduleFirst(std::move(task));
  };
}

void PoseGraph2D::RunOptimization(int max_iterations) {
  const auto start = std::chrono::steady_clock::now();
  SparsePoseAdjustment2D problem;
  // Graph indices of the problem's submaps and nodes: trimmed ones are left out.
  std::vector<int> submap_ids, node_ids;
  std::vector<std::pair<int, int>> solved_loops;  // (node, submap) of its loop closures
  common::Rigid2d T_local_last_node;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<int> submap_slot(submaps_.size(), -1), node_slot(nodes_.size(), -1);
    for (size_t s = 0; s < submaps_.size(); ++s) {
      if (submaps_[s].trimmed) continue;
      submap_slot[s] = problem.AddSubmap(T_map_submaps_[s]);
      submap_ids.push_back(static_cast<int>(s));
    }
    for (size_t n = 0; n < nodes_.size(); ++n) {
      if (nodes_[n].trimmed) continue;
      node_slot[n] = problem.AddNode(T_map_nodes_[n]);
      node_ids.push_back(nodes_[n].index);
    }
    for (Constraint2D constraint : constraints_) {
      if (constraint.tag == Constraint2D::kLoopClosureCandidate) continue;
      if (constraint.tag == Constraint2D::kInterSubmap) {
        solved_loops.emplace_back(constraint.node, constraint.submap);
      }
      if (constraint.tag == Constraint2D::kIntraSubmap) {
        // A node's place in its submap along a direction its scan did not pin is the
        // odometry's, as its step is: where the camera measured that step, neither holds the
        // odometry's scale error against it (the node-to-node steps below).
        const NodeData& node = nodes_[SlotLocked(constraint.node)];
        if (node.motion_linked) constraint.unmeasured_direction = node.unmeasured_direction;
      }
      constraint.submap = submap_slot[constraint.submap];
      constraint.node = node_slot[SlotLocked(constraint.node)];
      problem.AddConstraint(constraint);
    }
    for (size_t i = 0; i + 1 < nodes_.size(); ++i) {
      // Not across a node that is gone (trimmed, or removed after trimming).
      if (node_slot[i] < 0 || node_slot[i + 1] < 0 || nodes_[i + 1].index != nodes_[i].index + 1) {
        continue;
      }
      NodeToNodeConstraint2D c;
      c.from = node_slot[i];
      c.to = node_slot[i + 1];
      c.T_from_to = nodes_[i].T_local_node.inverse() * nodes_[i + 1].T_local_node;
      c.translation_weight = options_.local_slam_translation_weight;
      c.rotation_weight = options_.local_slam_rotation_weight;
      if (nodes_[i + 1].motion_linked) {
        c.weak_direction = nodes_[i + 1].unmeasured_direction;
        c.weak_weight_fraction = options_.linked_unmeasured_weight_fraction;
      }
      problem.AddNodeToNodeConstraint(c);
    }
    for (const NodeLink2D& link : node_links_) {
      const int from = SlotLocked(link.from);
      const int to = SlotLocked(link.to);
      if (from < 0 || to < 0 || node_slot[from] < 0 || node_slot[to] < 0) continue;
      NodeToNodeConstraint2D c;
      c.from = node_slot[from];
      c.to = node_slot[to];
      c.T_from_to = link.T_from_to;
      c.translation_weight = link.translation_weight;
      c.rotation_weight = link.rotation_weight;
      c.robust = true;  // the camera may have matched the wrong thing
      problem.AddNodeToNodeConstraint(c);
    }
    if (!nodes_.empty()) T_local_last_node = nodes_.back().T_local_node;
  }
  if (node_ids.empty()) {
    std::lock_guard<std::mutex> lock(mutex_);
    optimization_running_ = false;
    return;
  }
  OptimizationOptions solve_options = options_.optimization;
  solve_options.max_num_iterations = max_iterations;
  problem.Solve(solve_options);

  std::vector<SubmapMove> moved;
  std::vector<SubmapsMovedCallback> callbacks;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    // The newest node is never trimmed (its submaps are still active), so the graph ends with
    // node_ids.back() + 1 nodes as the problem was built. Nodes removed meanwhile were
    // trimmed before it was built, so every node_ids entry is still held.
    const int num_nodes = node_ids.back() + 1;
    const size_t num_submaps = submap_ids.empty() ? 0 : submap_ids.back() + 1;
    const std::vector<common::Rigid2d> before(T_map_submaps_.begin(),
                                              T_map_submaps_.begin() + num_submaps);
    for (size_t i = 0; i < node_ids.size(); ++i) {
      T_map_nodes_[SlotLocked(node_ids[i])] = problem.T_map_nodes()[i];
    }
    for (size_t i = 0; i < submap_ids.size(); ++i) {
      T_map_submaps_[submap_ids[i]] = problem.T_map_submaps()[i];
    }
    // Work added while solving follows the correction of the last optimised node.
    const common::Rigid2d T_map_local =
        T_map_nodes_[SlotLocked(num_nodes - 1)] * T_local_last_node.inverse();
    for (size_t i = 0; i < nodes_.size(); ++i) {
      if (nodes_[i].index >= num_nodes) T_map_nodes_[i] = T_map_local * nodes_[i].T_local_node;
    }
    for (size_t i = num_submaps; i < submaps_.size(); ++i) {
      T_map_submaps_[i] = T_map_local * submaps_[i].submap->T_local_submap();
    }
    moved = MovedSubmaps(before, std::vector<common::Rigid2d>(
                                     T_map_submaps_.begin(), T_map_submaps_.begin() + num_submaps));
    SetSolvedClosuresLocked(solved_loops);
    ++solve_count_;
    ++stats_.optimizations;
    stats_.optimization_s += SecondsSince(start);
    callbacks = callbacks_;
  }
  if (!moved.empty()) {
    for (const auto& callback : callbacks) callback(moved);
  }
  // Still flagged as running, so no other optimisation builds its problem from a graph that
  // is being trimmed.
  MaybeTrim();
  std::lock_guard<std::mutex> lock(mutex_);
  optimization_running_ = false;
}

void PoseGraph2D::MaybeTrim() {
  const OverlappingSubmapsTrimmerOptions2D& trimmer = options_.overlapping_submaps_trimmer;
  if (!trimmer.enabled()) return;
  std::vector<PlacedSubmap2D> placed;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (stats_.finished_submaps - finished_submaps_at_last_trim_ < trimmer.min_added_submaps_count) {
      return;
    }
    finished_submaps_at_last_trim_ = stats_.finished_submaps;
    for (size_t s = 0; s < submaps_.size(); ++s) {
      const SubmapData& data = submaps_[s];
      if (!data.finished || data.trimmed) continue;
      placed.push_back({static_cast<int>(s),
                        T_map_submaps_[s] * data.submap->T_local_submap().inverse(),
                        [submap = data.submap] { return submap->grid(); }});
    }
  }
  // Finished grids are immutable, so coverage is computed without holding the lock; each
  // placed submap holds its submap, so trimming meanwhile cannot free it.
  const auto start = std::chrono::steady_clock::now();
  const std::vector<int> trim = FindSubmapsToTrim(placed, trimmer);
  std::lock_guard<std::mutex> lock(mutex_);
  TrimLocked(trim);
  stats_.trimming_s += SecondsSince(start);
}

void PoseGraph2D::TrimLocked(const std::vector<int>& submaps) {
  if (submaps.empty() || nodes_.empty()) return;
  // Local SLAM may still insert into the newest node's submaps (a just finished one is dropped
  // from its active pair only on the next insertion), so those stay.
  const std::vector<int>& in_use = nodes_.back().inserted_into;
  bool any = false;
  for (int s : submaps) {
    SubmapData& data = submaps_[s];
    if (data.trimmed || std::find(in_use.begin(), in_use.end(), s) != in_use.end()) continue;
    submap_index_.erase(data.submap.get());
    data.submap.reset();
    if (data.matcher) matcher_bytes_ -= data.matcher->bytes();
    data.matcher.reset();
    data.searchable = false;
    data.waiting.clear();
    data.trimmed = true;
    ++stats_.trimmed_submaps;
    any = true;
  }
  if (!any) return;
  const auto submap_trimmed = [this](const Constraint2D& c) { return submaps_[c.submap].trimmed; };
  constraints_.erase(std::remove_if(constraints_.begin(), constraints_.end(), submap_trimmed),
                     constraints_.end());
  // A node is kept while some remaining submap holds it.
  std::vector<bool> held(nodes_.size(), false);
  for (const auto& c : constraints_) {
    if (c.tag == Constraint2D::kIntraSubmap) held[SlotLocked(c.node)] = true;
  }
  for (size_t n = 0; n < nodes_.size(); ++n) {
    NodeData& node = nodes_[n];
    if (node.trimmed || held[n]) continue;
    node.trimmed = true;
    sensor::PointCloud2d().swap(node.cloud);
    std::vector<int>().swap(node.inserted_into);
    ++stats_.trimmed_nodes;
  }
  const auto node_trimmed = [this](const Constraint2D& c) { return NodeGoneLocked(c.node); };
  constraints_.erase(std::remove_if(constraints_.begin(), constraints_.end(), node_trimmed),
                     constraints_.end());
  // Queued searches of a dropped pair go: ready ones (by their key) and all in flight.
  const auto drop_unheld = [this](auto& searches) {
    for (auto it = searches.begin(); it != searches.end();) {
      const PendingSearch2D& search = it->second;
      it = PairHeldLocked(search.node, search.submap) ? std::next(it) : searches.erase(it);
    }
  };
  drop_unheld(ready_searches_);
  drop_unheld(searches_in_flight_);
}

void PoseGraph2D::AddSubmapsMovedCallback(SubmapsMovedCallback callback) {
  std::lock_guard<std::mutex> lock(mutex_);
  callbacks_.push_back(std::move(callback));
}

std::vector<SubmapPlacement> PoseGraph2D::TakeSubmapPlacements() {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<SubmapPlacement> placements;
  // Poses change only in solves; without one, only new submaps need placing.
  const size_t first = solve_count_ != placed_solve_count_ ? 0 : T_map_submaps_placed_.size();
  placed_solve_count_ = solve_count_;
  for (size_t i = first; i < T_map_submaps_.size(); ++i) {
    const int submap = static_cast<int>(i);
    if (i >= T_map_submaps_placed_.size()) {
      T_map_submaps_placed_.push_back(T_map_submaps_[i]);
      placements.push_back({submap, T_map_submaps_[i], true});
    } else if (SubmapMoved(T_map_submaps_placed_[i], T_map_submaps_[i])) {
      T_map_submaps_placed_[i] = T_map_submaps_[i];
      placements.push_back({submap, T_map_submaps_[i], false});
    }
  }
  return placements;
}

void PoseGraph2D::RunFinalOptimization() {
  executor_->WaitIdle();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (options_.optimize_every_n_nodes == 0) return;
    optimization_running_ = true;
  }
  RunOptimization(options_.final_optimization_iterations);
  // The searches are over: the precomputation grids (up to matcher_memory_budget_mb) go back
  // before the caller draws its map. Were more data to come, a search would rebuild its grid.
  std::lock_guard<std::mutex> lock(mutex_);
  for (SubmapData& data : submaps_) data.matcher.reset();
  matcher_bytes_ = 0;
}

std::shared_ptr<const PoseGraphSnapshot> PoseGraph2D::Snapshot() const {
  auto snapshot = std::make_shared<PoseGraphSnapshot>();
  std::lock_guard<std::mutex> lock(mutex_);
  snapshot->solve_count = solve_count_;
  snapshot->node_ids.reserve(nodes_.size());
  for (const auto& node : nodes_) snapshot->node_ids.push_back(node.index);
  snapshot->T_map_submaps = T_map_submaps_;
  snapshot->T_map_nodes = T_map_nodes_;
  return snapshot;
}

std::vector<std::shared_ptr<const mapping::Submap2D>> PoseGraph2D::submaps() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<std::shared_ptr<const mapping::Submap2D>> result;
  for (const auto& s : submaps_) result.push_back(s.submap);
  return result;
}

std::vector<double> PoseGraph2D::node_stamps_s() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<double> stamps;
  for (const auto& n : nodes_) stamps.push_back(n.stamp_s);
  return stamps;
}

int PoseGraph2D::SlotLocked(int node) const {
  const auto it = std::lower_bound(nodes_.begin(), nodes_.end(), node,
                                   [](const NodeData& n, int index) { return n.index < index; });
  return it != nodes_.end() && it->index == node ? static_cast<int>(it - nodes_.begin()) : -1;
}

std::vector<ArchivedNode2D> PoseGraph2D::TrimmedNodes() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<ArchivedNode2D> trimmed;
  for (size_t i = 0; i < nodes_.size(); ++i) {
    if (nodes_[i].trimmed) trimmed.push_back({nodes_[i].index, nodes_[i].stamp_s, T_map_nodes_[i]});
  }
  return trimmed;
}

void PoseGraph2D::RemoveTrimmedNodes(const std::vector<int>& nodes) {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<bool> remove(nodes_.size(), false);
  for (int node : nodes) {
    const int slot = SlotLocked(node);
    if (slot >= 0 && nodes_[slot].trimmed) remove[slot] = true;
  }
  size_t kept = 0;
  for (size_t i = 0; i < nodes_.size(); ++i) {
    if (remove[i]) continue;
    if (kept != i) {
      nodes_[kept] = std::move(nodes_[i]);
      T_map_nodes_[kept] = T_map_nodes_[i];
    }
    ++kept;
  }
  nodes_.resize(kept);
  T_map_nodes_.resize(kept);
  node_links_.erase(std::remove_if(node_links_.begin(), node_links_.end(),
                                   [this](const NodeLink2D& link) {
                                     return SlotLocked(link.from) < 0 || SlotLocked(link.to) < 0;
                                   }),
                    node_links_.end());
}

common::Rigid2d PoseGraph2D::T_map_local() const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (nodes_.empty()) return common::Rigid2d::Identity();
  return T_map_nodes_.back() * nodes_.back().T_local_node.inverse();
}

int PoseGraph2D::SubmapIndex(const mapping::Submap2D* submap) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = submap_index_.find(submap);
  return it == submap_index_.end() ? -1 : it->second;
}

PoseGraph2D::Stats PoseGraph2D::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  Stats stats = stats_;
  stats.constraints = static_cast<int>(constraints_.size());
  stats.node_links = static_cast<int>(node_links_.size());
  stats.loop_closure_candidates = static_cast<int>(
      std::count_if(constraints_.begin(), constraints_.end(), [](const Constraint2D& c) {
        return c.tag == Constraint2D::kLoopClosureCandidate;
      }));
  stats.pending_searches = static_cast<int>(searches_in_flight_.size());
  stats.matcher_bytes = matcher_bytes_;
  for (const SubmapData& data : submaps_) {
    // Only finished grids: local SLAM may be growing the others on its own thread.
    if (data.submap && data.finished) {
      stats.submap_bytes += data.submap->grid_bytes();
      ++stats.finished_submaps_held;
    }
    if (data.matcher) ++stats.matchers;
  }
  for (const NodeData& node : nodes_) {
    stats.node_bytes += sizeof(NodeData) + node.cloud.capacity() * sizeof(Eigen::Vector2f) +
                        node.inserted_into.capacity() * sizeof(int);
    stats.linked_unmeasured_steps += node.motion_linked && !node.unmeasured_direction.isZero();
  }
  return stats;
}

}  // namespace pose_graph
}  // namespace fusemap
