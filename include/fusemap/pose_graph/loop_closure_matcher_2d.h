#ifndef FUSEMAP_POSE_GRAPH_LOOP_CLOSURE_MATCHER_2D_H_
#define FUSEMAP_POSE_GRAPH_LOOP_CLOSURE_MATCHER_2D_H_

#include <memory>
#include <optional>
#include <string>

#include "fusemap/common/config_reader.h"
#include "fusemap/common/rigid_transform.h"
#include "fusemap/mapping/scan_matching/ceres_scan_matcher_2d.h"
#include "fusemap/mapping/scan_matching/fast_correlative_scan_matcher_2d.h"
#include "fusemap/mapping/submap_2d.h"
#include "fusemap/pose_graph/pose_graph_types.h"
#include "fusemap/sensor/sensor_types.h"

namespace fusemap {
namespace pose_graph {

// The options of loop-closure search, under the profile key global_slam.constraint_builder
// (Cartographer's name). Which node is searched against which submap, and when, is decided
// by PoseGraph2D; this file holds the matcher one search runs.
struct ConstraintBuilderOptions2D {
  // Fraction of (node, submap) pairs in range that are searched (Cartographer's sampling_ratio).
  double sampling_ratio = 0.3;
  double max_constraint_distance_m = 15.0;
  // 100x Cartographer's: a log that keeps few scans has few closures per submap, and under the
  // Huber loss each pulls with a force capped by its weight; at 1.1e4 they lost to the 1e5
  // local SLAM chain (Intel relation error 0.073 m vs 0.054 m at 1.1e6).
  double loop_closure_translation_weight = 1.1e6;
  double loop_closure_rotation_weight = 1e7;
  // A match of a scan whose translation information along its weakest direction is below this
  // fraction of that along its strongest (mapping::ScanInformation2D::TranslationRatio) measures
  // nothing along that direction: in a corridor of plain walls the match slides along it at no
  // cost, so where it lands there says nothing about where the node is. Its constraint holds
  // the node across the corridor and in heading only (Constraint2D::unmeasured_direction). Such
  // scans measure below 0.005, scans that see a corner or a doorway above 0.05 (simulator
  // corridor, 2,653 matches). 0 takes every match as measuring every way.
  double min_translation_information_ratio = 0.02;
  // A match is taken only if drift explains how far it moves the node from where the graph
  // put it: at most max_correction_m (the match's own error) plus max_correction_per_path_m
  // (local SLAM's drift per metre) times the path travelled between the node and the submap
  // (DriftExplainsCorrection). In a floor of identical rooms or a corridor of identical doors
  // the scan matches the neighbouring one as well, a room or door spacing from the estimate.
  // Simulator rooms and corridor (5,000 matches): right ones moved the node at most 0.56 m,
  // wrong ones 1-4 m, also after 80 m of path; shared logs: 2 % of the path covers every
  // closure whose correction did not exceed the search window anyway. 0 for
  // max_correction_m takes every match.
  double max_correction_m = 0.5;
  double max_correction_per_path_m = 0.02;
  // The search's linear window follows the same bound (LoopSearchWindowM): never below
  // fast_correlative_scan_matcher.linear_search_window_m, never above this. A long corridor's
  // revisit after hundreds of metres without a closure lies further from where the graph puts
  // it than a fixed window reaches (freiburg-campus: its last leg 12 m along its first, 580 m
  // of path later). Equal to linear_search_window_m: a fixed window. A wider window reaches
  // more places a scan fits by chance, so PoseGraph2D holds a match from a widened search back
  // until another loop closure agrees with it (loop_closure_verification's pairwise test, with
  // at least one partner even where verification is off).
  double max_linear_search_window_m = 12.0;
  // A match that moves the node more than max_unevidenced_correction_m from the estimate is
  // taken only if the scan fits the submap there better than at the estimate by at least
  // min_correction_evidence_z standard errors of the per-point gain (EvidenceSupportsCorrection):
  // a match one room or a corridor's slide away fits about as well as the estimate, and a score
  // above min_score does not tell the two apart. Simulator rooms and corridor (3,649 right
  // matches): no right one moved the node more than 0.2 m; the wrong ones that drift explained
  // moved it 0.30 and 0.42 m with evidence 0.35 and 0.94. Shared logs (--threads 2): the
  // matches below 3 moved the node 0.21-0.32 m at 1.1-2.9 (aces, intel, seattle); 2 keeps the
  // ones above 2 (aces' two, RMSE 0.145-0.177 m without them) and refuses intel's and seattle's
  // at 1.1-1.5. 0 for min_correction_evidence_z takes every match.
  double max_unevidenced_correction_m = 0.2;
  double min_correction_evidence_z = 2.0;
  // A match also passes in a submap where it reaches this fraction of the submap's own fit
  // (the median score of the scans inserted into it, at the poses local SLAM gave them), when
  // that is below fast_correlative_scan_matcher.min_score. What a right match scores follows
  // how crisp the submap is: offices' own scans score 0.64-0.70, open halls' and outdoor ones
  // 0.56-0.60, a scan revisiting them less, so one fixed threshold that refuses wrong matches
  // in offices refuses nearly every right one outdoors. A submap whose own scans score below
  // min_score (blurred: local SLAM failed there) keeps min_score. 0 keeps it everywhere.
  double min_score_of_own_fit = 0.85;
  mapping::FastCorrelativeScanMatcherOptions2D fast_correlative_scan_matcher;
  mapping::CeresScanMatcherOptions2D ceres_scan_matcher;

  ConstraintBuilderOptions2D();
  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

// Keys: sampling_ratio, max_constraint_distance_m, loop_closure_translation_weight,
// loop_closure_rotation_weight, min_translation_information_ratio, max_correction_m,
// max_correction_per_path_m, max_linear_search_window_m, max_unevidenced_correction_m,
// min_correction_evidence_z, min_score_of_own_fit, fast_correlative_scan_matcher,
// ceres_scan_matcher.
ConstraintBuilderOptions2D ParseConstraintBuilderOptions2D(common::ConfigReader& reader);

// Whether local SLAM's drift over `path_m` of travel explains a loop closure that moves the node
// from `T_submap_node_estimate` (where the graph put it when the search was queued) to
// `T_submap_node_match`, by the translation bound above. Always true with max_correction_m 0.
bool DriftExplainsCorrection(const common::Rigid2d& T_submap_node_estimate,
                             const common::Rigid2d& T_submap_node_match, double path_m,
                             const ConstraintBuilderOptions2D& options);

// The linear search window for a node and a submap `path_m` of travel apart: the correction
// drift explains there (DriftExplainsCorrection), within [linear_search_window_m,
// max_linear_search_window_m]; linear_search_window_m with max_correction_m 0.
double LoopSearchWindowM(double path_m, const ConstraintBuilderOptions2D& options);

// Whether the match's evidence (Constraint2D::evidence_z) supports how far it moves the node
// from `T_submap_node_estimate` to `T_submap_node_match` (max_unevidenced_correction_m,
// min_correction_evidence_z). Always true with min_correction_evidence_z 0.
bool EvidenceSupportsCorrection(const common::Rigid2d& T_submap_node_estimate,
                                const common::Rigid2d& T_submap_node_match, double evidence_z,
                                const ConstraintBuilderOptions2D& options);

// The score a loop-closure match must exceed in a submap whose own fit is `own_fit` (0: not
// measured): fast_correlative_scan_matcher.min_score, or min_score_of_own_fit x own_fit where
// that is lower and the own fit itself reaches min_score.
double MinScoreForOwnFit(double own_fit, const ConstraintBuilderOptions2D& options);

// A finished submap prepared for loop closure: its precomputation grids are built once
// (the expensive part) and then shared read-only by every search against it.
class LoopClosureMatcher2D {
 public:
  LoopClosureMatcher2D(std::shared_ptr<const mapping::Submap2D> submap,
                       const ConstraintBuilderOptions2D& options);

  // Searches for `cloud` (tracking frame) in the submap around the estimate T_submap_node.
  // Returns a kInterSubmap constraint (with submap/node indices left for the caller) if the
  // branch-and-bound score exceeds `min_score`; `score` receives the best score found. For a
  // degenerate scan (min_translation_information_ratio) the constraint's unmeasured_direction
  // is set and its translation along it is the estimate's: the match's is no measurement, and
  // the constraint holds nothing there. The constraint's evidence_z compares its pose with the
  // estimate.
  // The linear window is LoopSearchWindowM(path_m): `path_m` is the travel between the node
  // and the submap (0: the configured linear_search_window_m).
  std::optional<Constraint2D> Match(const common::Rigid2d& T_submap_node_estimate,
                                    const sensor::PointCloud2d& cloud, double min_score,
                                    double* score, double path_m = 0.0) const;
  // The score a match of `cloud` at T_submap_node itself would have (no search).
  double ScoreAt(const common::Rigid2d& T_submap_node, const sensor::PointCloud2d& cloud) const;
  // Memory held by the precomputation grids (the submap is counted by its owner).
  size_t bytes() const { return fast_matcher_.precomputation_grids().bytes(); }

 private:
  std::shared_ptr<const mapping::Submap2D> submap_;
  const ConstraintBuilderOptions2D options_;
  mapping::FastCorrelativeScanMatcher2D fast_matcher_;
  mapping::CeresScanMatcher2D ceres_matcher_;
};

// Deterministic sampler: lets through the smallest number of pulses that keeps the passed
// fraction at or above `ratio` (Cartographer's FixedRatioSampler).
class FixedRatioSampler {
 public:
  explicit FixedRatioSampler(double ratio) : ratio_(ratio) {}
  bool Pulse() {
    ++num_pulses_;
    if (static_cast<double>(num_samples_) / num_pulses_ < ratio_) {
      ++num_samples_;
      return true;
    }
    return false;
  }

 private:
  double ratio_;
  long num_pulses_ = 0;
  long num_samples_ = 0;
};

}  // namespace pose_graph
}  // namespace fusemap

#endif  // FUSEMAP_POSE_GRAPH_LOOP_CLOSURE_MATCHER_2D_H_
