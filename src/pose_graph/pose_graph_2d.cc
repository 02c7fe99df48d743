#include "fusemap/pose_graph/pose_graph_2d.h"

#include <chrono>

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
  optimization.max_num_iterations = 10;
}

bool PoseGraphOptions2D::IsValid(std::string* error) const {
  if (optimize_every_n_nodes < 0 || final_optimization_iterations < 1) {
    *error = "optimize_every_n_nodes must be >= 0 and final_optimization_iterations >= 1";
    return false;
  }
  if (matcher_translation_weight <= 0 || matcher_rotation_weight <= 0 ||
      local_slam_translation_weight < 0 || local_slam_rotation_weight < 0) {
    *error = "constraint weights must be positive";
    return false;
  }
  return constraint_builder.IsValid(error) && optimization.IsValid(error);
}

PoseGraphOptions2D ParsePoseGraphOptions2D(common::ConfigReader& reader) {
  PoseGraphOptions2D options;
  reader.Get("optimize_every_n_nodes", &options.optimize_every_n_nodes);
  options.constraint_builder = ParseConstraintBuilderOptions2D(reader.Child("constraint_builder"));
  if (reader.Has("optimization")) {
    options.optimization = ParseOptimizationOptions(reader.Child("optimization"));
  }
  reader.Get("matcher_translation_weight", &options.matcher_translation_weight);
  reader.Get("matcher_rotation_weight", &options.matcher_rotation_weight);
  reader.Get("local_slam_translation_weight", &options.local_slam_translation_weight);
  reader.Get("local_slam_rotation_weight", &options.local_slam_rotation_weight);
  reader.Get("final_optimization_iterations", &options.final_optimization_iterations);
  std::string error;
  if (!options.IsValid(&error)) reader.AddError("optimize_every_n_nodes", error);
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
  int node;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const common::Rigid2d T_map_local = nodes_.empty()
                                            ? common::Rigid2d::Identity()
                                            : T_map_nodes_.back() * nodes_.back().T_local_node.inverse();
    node = static_cast<int>(nodes_.size());
    nodes_.push_back({stamp_s, T_local_node, filtered_cloud, {}});
    T_map_nodes_.push_back(T_map_local * T_local_node);
    ++stats_.nodes;

    for (const auto& submap : insertion_submaps) {
      const int s = SubmapIndexLocked(submap, T_map_local);
      nodes_[node].inserted_into.push_back(s);
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
        tasks.push_back(MakeMatcherTask(s, submap, true, {}));
      }
    }
    if (options_.optimize_every_n_nodes == 0) return node;
    // The new node against every finished submap near it.
    for (int s = 0; s < static_cast<int>(submaps_.size()); ++s) {
      if (submaps_[s].matcher) ScheduleSearchLocked(node, s);
    }
    if (++nodes_since_optimization_ >= options_.optimize_every_n_nodes && !optimization_running_) {
      nodes_since_optimization_ = 0;
      optimization_running_ = true;
      pending_tasks_.push_back([this] { RunOptimization(options_.optimization.max_num_iterations); });
    }
    tasks.insert(tasks.end(), pending_tasks_.begin(), pending_tasks_.end());
    pending_tasks_.clear();
  }
  // Scheduled outside the lock: an inline executor runs the task right here.
  for (auto& task : tasks) executor_->Schedule(std::move(task));
  return node;
}

void PoseGraph2D::ScheduleSearchLocked(int node, int submap) {
  const NodeData& node_data = nodes_[node];
  SubmapData& submap_data = submaps_[submap];
  for (int s : node_data.inserted_into) {
    if (s == submap) return;
  }
  const common::Rigid2d T_submap_node = T_map_submaps_[submap].inverse() * T_map_nodes_[node];
  if (T_submap_node.translation().norm() > options_.constraint_builder.max_constraint_distance_m) {
    return;
  }
  ++submap_data.sampler_pulses;
  if (!submap_data.sampler.Pulse()) return;
  QueueSearchLocked({node, submap, T_submap_node});
}

void PoseGraph2D::QueueSearchLocked(const PendingSearch2D& search) {
  const std::uint64_t id = next_search_id_++;
  searches_in_flight_[id] = search;
  auto matcher = submaps_[search.submap].matcher;
  auto cloud = std::make_shared<const sensor::PointCloud2d>(nodes_[search.node].cloud);
  pending_tasks_.push_back([this, matcher, cloud, search, id] {
    const auto start = std::chrono::steady_clock::now();
    double score = 0.0;
    std::optional<Constraint2D> constraint = matcher->Match(search.T_submap_node, *cloud, &score);
    std::lock_guard<std::mutex> lock(mutex_);
    searches_in_flight_.erase(id);
    stats_.loop_closure_search_s += SecondsSince(start);
    ++stats_.loop_closure_searches;
    if (!constraint) return;
    constraint->submap = search.submap;
    constraint->node = search.node;
    constraints_.push_back(*constraint);
    ++stats_.loop_closures_found;
  });
}

std::function<void()> PoseGraph2D::MakeMatcherTask(
    int s, std::shared_ptr<const mapping::Submap2D> submap, bool search_all_nodes,
    std::vector<PendingSearch2D> searches) {
  return [this, s, submap, search_all_nodes, searches] {
    const auto start = std::chrono::steady_clock::now();
    auto matcher =
        std::make_shared<const LoopClosureMatcher2D>(submap, options_.constraint_builder);
    std::vector<std::function<void()>> tasks;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stats_.precomputation_s += SecondsSince(start);
      submaps_[s].matcher = matcher;
      for (const auto& search : searches) QueueSearchLocked(search);
      if (search_all_nodes) {
        for (int n = 0; n < static_cast<int>(nodes_.size()); ++n) ScheduleSearchLocked(n, s);
      }
      tasks.swap(pending_tasks_);
    }
    for (auto& task : tasks) executor_->Schedule(std::move(task));
  };
}

void PoseGraph2D::RunOptimization(int max_iterations) {
  const auto start = std::chrono::steady_clock::now();
  SparsePoseAdjustment2D problem;
  std::vector<common::Rigid2d> T_local_nodes;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& pose : T_map_submaps_) problem.AddSubmap(pose);
    for (const auto& pose : T_map_nodes_) problem.AddNode(pose);
    for (const auto& constraint : constraints_) problem.AddConstraint(constraint);
    for (size_t i = 0; i + 1 < nodes_.size(); ++i) {
      NodeToNodeConstraint2D c;
      c.from = static_cast<int>(i);
      c.to = static_cast<int>(i + 1);
      c.T_from_to = nodes_[i].T_local_node.inverse() * nodes_[i + 1].T_local_node;
      c.translation_weight = options_.local_slam_translation_weight;
      c.rotation_weight = options_.local_slam_rotation_weight;
      problem.AddNodeToNodeConstraint(c);
    }
    for (const auto& node : nodes_) T_local_nodes.push_back(node.T_local_node);
  }
  if (T_local_nodes.empty()) {
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
    const size_t num_nodes = problem.T_map_nodes().size();
    const size_t num_submaps = problem.T_map_submaps().size();
    const std::vector<common::Rigid2d> before(T_map_submaps_.begin(),
                                              T_map_submaps_.begin() + num_submaps);
    for (size_t i = 0; i < num_nodes; ++i) T_map_nodes_[i] = problem.T_map_nodes()[i];
    for (size_t i = 0; i < num_submaps; ++i) T_map_submaps_[i] = problem.T_map_submaps()[i];
    // Work added while solving follows the correction of the last optimised node.
    const common::Rigid2d T_map_local =
        T_map_nodes_[num_nodes - 1] * T_local_nodes[num_nodes - 1].inverse();
    for (size_t i = num_nodes; i < nodes_.size(); ++i) {
      T_map_nodes_[i] = T_map_local * nodes_[i].T_local_node;
    }
    for (size_t i = num_submaps; i < submaps_.size(); ++i) {
      T_map_submaps_[i] = T_map_local * submaps_[i].submap->T_local_submap();
    }
    moved = MovedSubmaps(before, problem.T_map_submaps());
    ++solve_count_;
    ++stats_.optimizations;
    stats_.optimization_s += SecondsSince(start);
    optimization_running_ = false;
    callbacks = callbacks_;
  }
  if (!moved.empty()) {
    for (const auto& callback : callbacks) callback(moved);
  }
}

void PoseGraph2D::AddSubmapsMovedCallback(SubmapsMovedCallback callback) {
  std::lock_guard<std::mutex> lock(mutex_);
  callbacks_.push_back(std::move(callback));
}

void PoseGraph2D::RunFinalOptimization() {
  executor_->WaitIdle();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (options_.optimize_every_n_nodes == 0) return;
    optimization_running_ = true;
  }
  RunOptimization(options_.final_optimization_iterations);
}

std::shared_ptr<const PoseGraphSnapshot> PoseGraph2D::Snapshot() const {
  auto snapshot = std::make_shared<PoseGraphSnapshot>();
  std::lock_guard<std::mutex> lock(mutex_);
  snapshot->solve_count = solve_count_;
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
  return stats_;
}

}  // namespace pose_graph
}  // namespace fusemap
