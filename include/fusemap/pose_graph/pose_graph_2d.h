#ifndef FUSEMAP_POSE_GRAPH_POSE_GRAPH_2D_H_
#define FUSEMAP_POSE_GRAPH_POSE_GRAPH_2D_H_

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fusemap/common/config_reader.h"
#include "fusemap/common/thread_pool.h"
#include "fusemap/mapping/submap_2d.h"
#include "fusemap/pose_graph/loop_closure_matcher_2d.h"
#include "fusemap/pose_graph/loop_closure_verifier_2d.h"
#include "fusemap/pose_graph/moved_submaps.h"
#include "fusemap/pose_graph/optimization_options.h"
#include "fusemap/pose_graph/overlapping_submaps_trimmer_2d.h"
#include "fusemap/pose_graph/pose_graph_snapshot.h"

namespace fusemap {
namespace pose_graph {

struct PoseGraphOptions2D {
  // Optimise after this many new nodes; 0 disables loop closure and optimisation entirely.
  int optimize_every_n_nodes = 35;
  ConstraintBuilderOptions2D constraint_builder;
  OptimizationOptions optimization;
  // Weights of the node-in-submap constraints from local SLAM (Cartographer's matcher_*).
  double matcher_translation_weight = 5e2;
  double matcher_rotation_weight = 1.6e3;
  // Weights of the relative motion between consecutive nodes as local SLAM estimated it.
  double local_slam_translation_weight = 1e5;
  double local_slam_rotation_weight = 1e5;
  // Where a node link (AddNodeLink: the camera's motion between keyframes) measured the motion
  // across a step whose scan pinned only one direction (a corridor of plain walls, by
  // constraint_builder.min_translation_information_ratio), local SLAM's step along the other
  // direction is the odometry's guess, scale error and all: its translation weight there is
  // this fraction of local_slam_translation_weight, so that the link decides it. 1: unchanged.
  double linked_unmeasured_weight_fraction = 1e-2;
  int final_optimization_iterations = 200;
  // Memory for loop-closure precomputation grids (LoopClosureMatcher2D) held at once. Beyond
  // it, the grids of the submaps least recently searched are released and rebuilt when a
  // search needs them again: a campus has tens of submaps of several MB each, and a search
  // reaches only the few within max_constraint_distance_m.
  double matcher_memory_budget_mb = 32.0;
  // Loop-closure searches queued at once. Beyond it the oldest node's search is dropped (and
  // counted): a daemon whose searches cannot keep up with the data drops stale ones, rather
  // than fall further behind without bound.
  int max_pending_searches = 2000;
  OverlappingSubmapsTrimmerOptions2D overlapping_submaps_trimmer;  // off by default
  LoopClosureVerificationOptions2D loop_closure_verification;      // off by default

  PoseGraphOptions2D();
  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

// Keys: optimize_every_n_nodes, constraint_builder, optimization, matcher_translation_weight,
// matcher_rotation_weight, local_slam_translation_weight, local_slam_rotation_weight,
// final_optimization_iterations, matcher_memory_budget_mb, max_pending_searches,
// overlapping_submaps_trimmer, loop_closure_verification.
PoseGraphOptions2D ParsePoseGraphOptions2D(common::ConfigReader& reader);

// A loop-closure search queued but not yet finished: node against submap, from the estimate.
struct PendingSearch2D {
  int node = 0;
  int submap = 0;
  common::Rigid2d T_submap_node;
};

struct PoseGraphState2D;

// A laser loop closure the graph accepted (PoseGraph2D::TakeNewLoopClosures).
struct LoopClosure2D {
  int id = -1;  // Constraint2D::loop_id
  int node = 0;
  int submap = 0;
  common::Rigid2d T_submap_node;
  double laser_score = 0.0;
  // Constraint2D::unmeasured_direction: zero unless the scan held the match across a
  // corridor only; Constraint2D::unmeasured_turn_rad_per_m with it.
  Eigen::Vector2d unmeasured_direction = Eigen::Vector2d::Zero();
  double unmeasured_turn_rad_per_m = 0.0;
};

// A loop constraint measured outside the graph (the visual loop checker): node in submap,
// with its weights (residual = weights .* error, as Constraint2D) and what measured it.
struct ExternalLoopConstraint2D {
  int node = 0;
  int submap = 0;
  common::Rigid2d T_submap_node;
  double translation_weight = 1.0;
  double rotation_weight = 1.0;
  Constraint2D::Source source = Constraint2D::kVisual;
  double laser_score = 0.0;  // with source kLaser
  // With source kLaser, what the match did not measure (Constraint2D::unmeasured_direction,
  // unmeasured_turn_rad_per_m); a visual loop measures every way.
  Eigen::Vector2d unmeasured_direction = Eigen::Vector2d::Zero();
  double unmeasured_turn_rad_per_m = 0.0;
};

// A relative pose between two nodes measured outside the graph: the camera's motion between
// consecutive keyframes (session::VisualStage), with its weights (residual = weights .* error,
// in the `to` node's frame, as Constraint2D).
struct NodeLink2D {
  int from = 0;
  int to = 0;  // from < to
  common::Rigid2d T_from_to;
  double translation_weight = 1.0;
  double rotation_weight = 1.0;
};

// A trimmed node with its final pose (PoseGraph2D::TrimmedNodes).
struct ArchivedNode2D {
  int node = 0;
  double stamp_s = 0.0;
  common::Rigid2d T_map_node;
};

// Global SLAM (Hess et al. 2016, Sec. V): collects local SLAM's nodes and submaps, searches
// loop closures against finished submaps with branch-and-bound, and periodically re-solves all
// poses with sparse pose adjustment. Searches and optimisations run as tasks on the given
// executor; with an InlineExecutor every call completes synchronously and runs are
// reproducible. With the overlapping submaps trimmer on, submaps and nodes may be trimmed after
// an optimisation: they keep their index and last pose, but their data is released and they
// take no further part. Trimmed nodes can then be taken out of memory altogether
// (RemoveTrimmedNodes), so that a graph that keeps trimming holds what the map needs, not what the
// run has seen; node indices stay those given by AddNode. The precomputation grids held at
// once stay within matcher_memory_budget_mb: released grids are rebuilt (on the executor) when
// a search needs them, which changes when searches run, never what they find. All public
// methods are thread-safe.
class PoseGraph2D {
 public:
  struct Stats {
    int nodes = 0;
    int submaps = 0;
    int finished_submaps = 0;
    int intra_constraints = 0;
    int loop_closure_searches = 0;
    int loop_closures_found = 0;
    int optimizations = 0;
    int trimmed_submaps = 0;
    int trimmed_nodes = 0;
    int constraints = 0;  // node-in-submap constraints in the graph now (not checkpointed)
    // Matches waiting for loop-closure verification now (not checkpointed; included in
    // constraints, not in loop_closures_found).
    int loop_closure_candidates = 0;
    // Loop closures found whose scan could slide along a corridor, held across it only
    // (constraint_builder.min_translation_information_ratio; not checkpointed).
    int loop_closures_degenerate = 0;
    // Matches refused because they move the node further than drift explains
    // (constraint_builder.max_correction_m; not checkpointed).
    int loop_closures_beyond_drift = 0;
    // Matches refused because they move the node beyond max_unevidenced_correction_m yet fit
    // hardly better than the estimate (constraint_builder.min_correction_evidence_z; not
    // checkpointed).
    int loop_closures_ambiguous = 0;
    // Node links held (AddNodeLink), and the local SLAM steps they cover whose scan pinned one
    // direction only (linked_unmeasured_weight_fraction; not checkpointed).
    int node_links = 0;
    int linked_unmeasured_steps = 0;
    // Loop-closure searches queued and not yet finished: now, and the most at any time since
    // the graph was made (not checkpointed).
    int pending_searches = 0;
    int max_pending_searches = 0;
    // Searches skipped because max_pending_searches were queued (not checkpointed).
    int searches_skipped = 0;
    // Memory held now (not checkpointed): grids of the finished submaps held (the active ones
    // belong to local SLAM), precomputation grids of the submaps prepared for loop closure,
    // and node point clouds.
    size_t submap_bytes = 0;
    int finished_submaps_held = 0;
    size_t matcher_bytes = 0;
    size_t node_bytes = 0;
    int matchers = 0;  // submaps whose precomputation grids are held
    // The most precomputation memory held at once since the graph was made, and the number of
    // submaps' grids that was (not checkpointed). RunFinalOptimization releases them all.
    size_t max_matcher_bytes = 0;
    int max_matchers = 0;
    // Precomputations run (first builds and rebuilds), and grids released to stay within
    // matcher_memory_budget_mb (not checkpointed).
    int matcher_builds = 0;
    int matcher_evictions = 0;
    double loop_closure_search_s = 0.0;
    double precomputation_s = 0.0;
    double optimization_s = 0.0;
    double trimming_s = 0.0;
  };
  using SubmapsMovedCallback = std::function<void(const std::vector<SubmapMove>&)>;

  PoseGraph2D(const PoseGraphOptions2D& options, common::Executor* executor);
  ~PoseGraph2D();
  PoseGraph2D(const PoseGraph2D&) = delete;
  PoseGraph2D& operator=(const PoseGraph2D&) = delete;

  // Adds a node (a scan local SLAM inserted). `insertion_submaps` are the submaps it went into,
  // oldest first; the front one may have just been finished. Returns the node index.
  int AddNode(double stamp_s, const common::Rigid2d& T_local_node,
              const sensor::PointCloud2d& filtered_cloud,
              const std::vector<std::shared_ptr<const mapping::Submap2D>>& insertion_submaps);

  // Called after each optimisation with the submaps whose pose changed (SubmapMoved), on
  // the thread that ran it: a notification for whoever publishes the submap list.
  void AddSubmapsMovedCallback(SubmapsMovedCallback callback);
  // What one consumer (session::SlamSession, for the cloud) must place since its previous
  // call: new submaps, and submaps an optimisation moved (SubmapMoved) away from the pose last
  // handed out, each at its current map pose. Comparing with what was handed out, not with the
  // pose before each optimisation, lets small moves add up until they count.
  std::vector<SubmapPlacement> TakeSubmapPlacements();

  // Waits for pending work, then runs a last, longer optimisation.
  void RunFinalOptimization();

  // Current global estimate: T_map_local applied to local poses of nodes not yet optimised.
  // Its T_map_nodes are those of the nodes still held (node_ids).
  std::shared_ptr<const PoseGraphSnapshot> Snapshot() const;
  // By index; null for trimmed submaps.
  std::vector<std::shared_ptr<const mapping::Submap2D>> submaps() const;
  // Stamps of the nodes still held, oldest first.
  std::vector<double> node_stamps_s() const;
  // The trimmed nodes still held, oldest first. Their poses are final: trimmed nodes are in no
  // optimisation problem.
  std::vector<ArchivedNode2D> TrimmedNodes() const;
  // Lets go of the trimmed nodes among `nodes` (indices), once whoever wants them has them.
  void RemoveTrimmedNodes(const std::vector<int>& nodes);
  common::Rigid2d T_map_local() const;
  // The index of a submap a node was inserted into, or -1 if no node has reached it yet.
  int SubmapIndex(const mapping::Submap2D* submap) const;
  Stats stats() const;

  // Loop constraints by id, for a second opinion on laser loops (session::VisualStage). All
  // take effect in the next optimisation, as a laser closure found by a search does.
  //
  // From now on, remember the laser loop closures accepted, for TakeNewLoopClosures (off by
  // default: without a taker the list would grow for the whole run).
  void ReportLoopClosures();
  // The laser loop closures accepted since the previous call, oldest first; ones removed or
  // trimmed meanwhile are left out.
  std::vector<LoopClosure2D> TakeNewLoopClosures();
  // Adds a loop closure; returns its id, or -1 if the node or the submap is gone (trimmed) or
  // was never added, or the node was inserted into that submap. One with source kLaser (a
  // laser loop found elsewhere) is reported by TakeNewLoopClosures like a search's.
  int AddLoopConstraint(const ExternalLoopConstraint2D& constraint);
  // Replaces the measurement, weights and source of loop closure `id` (its node and submap
  // stay); false if it is gone.
  bool ReplaceLoopConstraint(int id, const ExternalLoopConstraint2D& constraint);
  // Changes only what loop closure `id` is attributed to; false if it is gone.
  bool SetLoopConstraintSource(int id, Constraint2D::Source source);
  // Takes loop closure `id` out of the graph; false if it is gone.
  bool RemoveLoopConstraint(int id);
  // The loop closures (accepted or candidates) in the graph now.
  std::vector<Constraint2D> LoopConstraints() const;
  // Adds a measured relative pose between two nodes; it takes part in every optimisation until
  // either node is trimmed. False (and nothing added) unless from < to and both are held.
  bool AddNodeLink(const NodeLink2D& link);
  // The node links held, in the order added.
  std::vector<NodeLink2D> NodeLinks() const;
  // The path between node `node` and submap `submap` that the loop-closure drift bound allows
  // for (DriftExplainsCorrection): along the chain of nodes, or through a loop closure of the
  // last solved graph, whichever is shorter; empty if either is gone or unknown.
  std::optional<double> PathBetween(int node, int submap) const;
  // Where node `node` stands in submap `submap` by the current global estimate
  // (T_map_submap^-1 * T_map_node); empty if either is gone or unknown.
  std::optional<common::Rigid2d> T_submap_node(int submap, int node) const;

  // A consistent copy of the graph, taken under the lock without waiting for background
  // work: searches, precomputations and an optimisation still running are recorded and redone
  // by RestoreState(). `submaps` receives the submaps by index, null for trimmed ones (their
  // contents are not copied here; unfinished ones are still written by local SLAM).
  PoseGraphState2D ExportState(
      std::vector<std::shared_ptr<const mapping::Submap2D>>* submaps) const;
  // Only on a graph without nodes. `submaps` are the restored submaps by index (null where
  // trimmed). Finished submaps whose precomputation had not finished, or with searches
  // pending, get their grids rebuilt on the executor (until then new nodes are not searched
  // against them); the others rebuild theirs when a search first needs them.
  void RestoreState(const PoseGraphState2D& state,
                    const std::vector<std::shared_ptr<const mapping::Submap2D>>& submaps);

 private:
  struct NodeData {
    int index;  // as AddNode returned it
    double stamp_s;
    common::Rigid2d T_local_node;
    sensor::PointCloud2d cloud;
    std::vector<int> inserted_into;
    bool trimmed = false;  // cloud and inserted_into released
    // Path travelled in local SLAM's frame from the first node to this one.
    double path_m = 0.0;
    // A node link measured the motion from the node before to this one (AddNodeLink), and
    // this node's scan left this direction (its frame) unpinned; zero when it pinned both.
    bool motion_linked = false;
    Eigen::Vector2d unmeasured_direction = Eigen::Vector2d::Zero();
  };
  struct SubmapData {
    std::shared_ptr<const mapping::Submap2D> submap;
    // Held while precomputed and within the memory budget (matcher_memory_budget_mb).
    std::shared_ptr<const LoopClosureMatcher2D> matcher;
    bool finished = false;
    // Precomputed once and the search of every node near it queued: searched from then on,
    // rebuilding `matcher` when it was released.
    bool searchable = false;
    bool rebuilding = false;  // a precomputation task is queued or running
    std::uint64_t last_used = 0;  // use_clock_ at the last search queued against it
    // Searches (by id in searches_in_flight_) waiting for `matcher` to be rebuilt.
    std::vector<std::pair<std::uint64_t, PendingSearch2D>> waiting;
    bool trimmed = false;  // submap and matcher released
    FixedRatioSampler sampler{0.0};
    long sampler_pulses = 0;  // lets a restored sampler be replayed to the same state
    // NodeData::path_m of the first (-1 before it) and the last node inserted into it.
    double first_path_m = -1.0;
    double last_path_m = 0.0;
    // NodeData::path_m of the nodes that loop closures in the last solved graph tie to this
    // submap, ascending: shortcuts for PathBetweenLocked.
    std::vector<double> solved_closure_paths_m;
    // The median score of its own nodes' scans at their intra-submap poses (0 until measured,
    // when its first precomputation is installed): see MinScoreForOwnFit.
    double own_fit = 0.0;
  };

  // Ready searches (ready_searches_), best first: the newest node first, then first come. Behind
  // a backlog the closures of the node just added are worth the most: they tie where the robot
  // is now to the old map, which is what lets the trimmer release the old submaps; a search of
  // a node long past is about a stretch later closures have tied since. (-node, id).
  using ReadyKey = std::pair<int, std::uint64_t>;

  int SubmapIndexLocked(const std::shared_ptr<const mapping::Submap2D>& submap,
                        const common::Rigid2d& T_map_local);
  // Path travelled between node `node` (held) and the nearest node inserted into `submap`:
  // along the chain of nodes, or to a node that a solved loop closure ties to some submap and
  // on along the chain from that submap, whichever is shorter (drift accrues only along the
  // path since the graph last tied the two together).
  double PathBetweenLocked(int node, int submap) const;
  // Sets every submap's solved_closure_paths_m from `loops` (node, submap) of a solved graph.
  void SetSolvedClosuresLocked(const std::vector<std::pair<int, int>>& loops);
  // Queues a loop-closure search of `node` in `submap` if they are close and sampled.
  void ScheduleSearchLocked(int node, int submap);
  void QueueSearchLocked(const PendingSearch2D& search);
  // Search `id` waits for its submap's matcher, which is rebuilt if it is not being built.
  void WaitForMatcherLocked(std::uint64_t id, const PendingSearch2D& search);
  // Makes search `id`, whose submap's matcher is held, ready to run, and hands the executor a
  // task that runs the best ready search (RunBestSearch).
  void MakeSearchReadyLocked(std::uint64_t id, const PendingSearch2D& search);
  // Runs the ready search of the highest priority (ReadyKey), if any is left.
  void RunBestSearch();
  // Installs a just built matcher for submap `s`, then releases the least recently used
  // others while the grids held exceed the budget.
  void InstallMatcherLocked(int s, std::shared_ptr<const LoopClosureMatcher2D> matcher);
  // SubmapData::own_fit of submap s, measured with its matcher (0 without nodes left).
  double OwnFitLocked(int s, const LoopClosureMatcher2D& matcher);
  // Adds a found match: at once, or with verification on (or `needs_agreement`: it came from a
  // search widened beyond the configured window, LoopSearchWindowM) as a candidate that is
  // accepted (together with the candidates it confirms) once enough closures agree with it, at
  // least one. A match accepted at once still confirms the candidates it agrees with.
  void AddLoopClosureLocked(const Constraint2D& constraint, bool needs_agreement);
  // Builds the precomputation grids of finished submap `s`, then queues `searches`, and with
  // `search_all_nodes` a search of every node near it.
  std::function<void()> MakeMatcherTask(int s, std::shared_ptr<const mapping::Submap2D> submap,
                                        bool search_all_nodes,
                                        std::vector<PendingSearch2D> searches);
  void RunOptimization(int max_iterations);
  // Runs the overlapping submaps trimmer if enough submaps finished since it last ran.
  void MaybeTrim();
  // Drops `submaps`, their constraints, and the nodes left in no remaining submap.
  void TrimLocked(const std::vector<int>& submaps);
  // Where node `node` is in nodes_, -1 once RemoveTrimmedNodes removed it.
  int SlotLocked(int node) const;
  // `node` must be held.
  NodeData& NodeLocked(int node) { return nodes_[SlotLocked(node)]; }
  // Trimmed, or removed by RemoveTrimmedNodes.
  bool NodeGoneLocked(int node) const {
    const int slot = SlotLocked(node);
    return slot < 0 || nodes_[slot].trimmed;
  }
  // Both ends of a node-in-submap pair are known and still held (not trimmed).
  bool PairHeldLocked(int node, int submap) const {
    return submap >= 0 && submap < static_cast<int>(submaps_.size()) &&
           !submaps_[submap].trimmed && !NodeGoneLocked(node);
  }

  const PoseGraphOptions2D options_;
  common::Executor* const executor_;

  mutable std::mutex mutex_;
  // The nodes held, by increasing index (stats_.nodes were added in all).
  std::vector<NodeData> nodes_;              // guarded by mutex_
  std::vector<SubmapData> submaps_;          // guarded by mutex_
  std::map<const mapping::Submap2D*, int> submap_index_;  // guarded by mutex_
  std::vector<common::Rigid2d> T_map_nodes_;    // guarded by mutex_, like nodes_
  std::vector<common::Rigid2d> T_map_submaps_;  // guarded by mutex_
  std::vector<Constraint2D> constraints_;       // guarded by mutex_
  int nodes_since_optimization_ = 0;            // guarded by mutex_
  int finished_submaps_at_last_trim_ = 0;       // guarded by mutex_
  bool optimization_running_ = false;           // guarded by mutex_
  std::uint64_t solve_count_ = 0;               // guarded by mutex_
  Stats stats_;                                 // guarded by mutex_
  std::vector<SubmapsMovedCallback> callbacks_;  // guarded by mutex_
  // TakeSubmapPlacements: the poses it handed out, and the solves they reflect.
  std::vector<common::Rigid2d> T_map_submaps_placed_;  // guarded by mutex_
  std::uint64_t placed_solve_count_ = 0;               // guarded by mutex_
  // Work found while holding mutex_, handed to the executor once it is released: searches at
  // the back of its queue, precomputation (which the searches of a submap wait for) at the front.
  std::vector<std::function<void()>> pending_tasks_;        // guarded by mutex_
  std::vector<std::function<void()>> pending_first_tasks_;  // guarded by mutex_
  // RunBestSearch tasks handed out and not yet started.
  size_t search_tasks_outstanding_ = 0;  // guarded by mutex_
  // Searches queued and not yet finished, by a running id: ready or waiting for a matcher.
  std::map<std::uint64_t, PendingSearch2D> searches_in_flight_;  // guarded by mutex_
  std::map<ReadyKey, PendingSearch2D> ready_searches_;  // guarded by mutex_
  std::uint64_t next_search_id_ = 0;                             // guarded by mutex_
  std::uint64_t use_clock_ = 0;                                  // guarded by mutex_
  size_t matcher_bytes_ = 0;  // guarded by mutex_, of the matchers held
  // The loop-constraint API (pose_graph_2d_loops.cc).
  int next_loop_id_ = 0;                  // guarded by mutex_
  bool report_loop_closures_ = false;     // guarded by mutex_
  std::vector<int> new_loop_closures_;    // guarded by mutex_, ids
  std::vector<NodeLink2D> node_links_;    // guarded by mutex_
  // A node link's steps: the held, untrimmed nodes after link.from up to link.to that no link
  // has judged yet, with their scans; what each scan left unpinned (JudgeSteps, no lock needed:
  // AddNodeLink runs it outside the lock); and marking them motion_linked with it.
  using StepScans = std::vector<std::pair<int, sensor::PointCloud2d>>;
  using StepDirections = std::vector<std::pair<int, Eigen::Vector2d>>;
  StepScans UnjudgedStepsLocked(const NodeLink2D& link) const;
  StepDirections JudgeSteps(const StepScans& steps) const;
  void MarkJudgedStepsLocked(const StepDirections& directions);
  // The loop closure with `id`, or null.
  Constraint2D* FindLoopLocked(int id);
  // Records an accepted laser loop closure for TakeNewLoopClosures.
  void NoteAcceptedLocked(const Constraint2D& constraint);
};

// Everything PoseGraph2D holds besides its options and the submap grids, as plain values
// (checkpoints). Submaps are numbered as in PoseGraph2D; their grids travel separately. Nodes
// (and T_map_nodes) are the ones held, by increasing index; constraints and searches name them
// by that index.
struct PoseGraphState2D {
  struct Node {
    int index = 0;
    double stamp_s = 0.0;
    common::Rigid2d T_local_node;
    sensor::PointCloud2d cloud;
    std::vector<int> inserted_into;
    bool trimmed = false;
    double path_m = 0.0;
  };
  struct Submap {
    bool finished = false;
    bool trimmed = false;  // its grid is gone (MapBuilderState2D holds an empty one)
    bool matcher_ready = false;  // precomputed, and the searches of all nodes were queued
    long sampler_pulses = 0;
    double first_path_m = -1.0;
    double last_path_m = 0.0;
  };
  std::vector<Node> nodes;
  std::vector<Submap> submaps;
  std::vector<common::Rigid2d> T_map_nodes;
  std::vector<common::Rigid2d> T_map_submaps;
  std::vector<Constraint2D> constraints;
  std::vector<NodeLink2D> node_links;
  std::vector<PendingSearch2D> searches_in_flight;
  bool optimization_pending = false;
  int nodes_since_optimization = 0;
  int finished_submaps_at_last_trim = 0;
  std::uint64_t solve_count = 0;
  PoseGraph2D::Stats stats;
  int next_loop_id = 0;  // the next Constraint2D::loop_id
};

}  // namespace pose_graph
}  // namespace fusemap

#endif  // FUSEMAP_POSE_GRAPH_POSE_GRAPH_2D_H_
