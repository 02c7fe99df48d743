#include "fusemap/pose_graph/loop_closure_matcher_2d.h"

#include <algorithm>
#include <cmath>

#include "fusemap/mapping/scan_matching/match_evidence_2d.h"
#include "fusemap/mapping/scan_matching/scan_information_2d.h"

namespace fusemap {
namespace pose_graph {
namespace {

// The motion along an arc that starts in the direction of `translation_m`, is as long as it is
// and turns `turn_rad` at a constant rate: SE(2)'s exponential of that twist.
common::Rigid2d ArcMotion2D(const Eigen::Vector2d& translation_m, double turn_rad) {
  if (std::abs(turn_rad) < 1e-9) return common::Rigid2d(translation_m, turn_rad);
  const double a = std::sin(turn_rad) / turn_rad;
  const double b = (1.0 - std::cos(turn_rad)) / turn_rad;
  return common::Rigid2d(Eigen::Vector2d(a * translation_m.x() - b * translation_m.y(),
                                         b * translation_m.x() + a * translation_m.y()),
                         turn_rad);
}

}  // namespace

ConstraintBuilderOptions2D::ConstraintBuilderOptions2D() {
  // Loop closures trust the occupancy fit more and the search start less than local SLAM does
  // (Cartographer's constraint_builder.ceres_scan_matcher defaults).
  ceres_scan_matcher.occupied_space_weight = 20.0;
  ceres_scan_matcher.translation_weight = 10.0;
  ceres_scan_matcher.rotation_weight = 1.0;
  ceres_scan_matcher.max_num_iterations = 10;
  // A loop closure refines a match inside a finished submap, where a point in never-observed
  // space is evidence against the match, not the edge of new space as in local SLAM.
  ceres_scan_matcher.unknown_probability = mapping::kMinProbability;
}

void ConstraintBuilderOptions2D::Check(common::OptionChecker* check) const {
  check->Require(sampling_ratio >= 0.0 && sampling_ratio <= 1.0, "sampling_ratio",
                 "must be in [0, 1]");
  check->Require(max_constraint_distance_m > 0.0, "max_constraint_distance_m", "must be > 0");
  check->Require(loop_closure_translation_weight > 0.0, "loop_closure_translation_weight",
                 "must be > 0");
  check->Require(loop_closure_rotation_weight > 0.0, "loop_closure_rotation_weight",
                 "must be > 0");
  check->Require(
      min_translation_information_ratio >= 0.0 && min_translation_information_ratio <= 1.0,
      "min_translation_information_ratio", "must be in [0, 1]");
  check->Require(max_correction_m >= 0.0, "max_correction_m", "must be >= 0");
  check->Require(max_correction_per_path_m >= 0.0, "max_correction_per_path_m", "must be >= 0");
  check->Require(max_linear_search_window_m >= fast_correlative_scan_matcher.linear_search_window_m,
                 "max_linear_search_window_m",
                 "must be >= fast_correlative_scan_matcher.linear_search_window_m");
  check->Require(max_unevidenced_correction_m >= 0.0, "max_unevidenced_correction_m",
                 "must be >= 0");
  check->Require(min_correction_evidence_z >= 0.0, "min_correction_evidence_z", "must be >= 0");
  check->Require(min_score_of_own_fit >= 0.0 && min_score_of_own_fit <= 1.0,
                 "min_score_of_own_fit", "must be in [0, 1]");
  check->Nested("fast_correlative_scan_matcher", fast_correlative_scan_matcher);
  check->Nested("ceres_scan_matcher", ceres_scan_matcher);
}

bool ConstraintBuilderOptions2D::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

ConstraintBuilderOptions2D ParseConstraintBuilderOptions2D(common::ConfigReader& reader) {
  ConstraintBuilderOptions2D options;
  reader.Get("sampling_ratio", &options.sampling_ratio);
  reader.Get("max_constraint_distance_m", &options.max_constraint_distance_m);
  reader.Get("loop_closure_translation_weight", &options.loop_closure_translation_weight);
  reader.Get("loop_closure_rotation_weight", &options.loop_closure_rotation_weight);
  reader.Get("min_translation_information_ratio", &options.min_translation_information_ratio);
  reader.Get("max_correction_m", &options.max_correction_m);
  reader.Get("max_correction_per_path_m", &options.max_correction_per_path_m);
  reader.Get("max_linear_search_window_m", &options.max_linear_search_window_m);
  reader.Get("max_unevidenced_correction_m", &options.max_unevidenced_correction_m);
  reader.Get("min_correction_evidence_z", &options.min_correction_evidence_z);
  reader.Get("min_score_of_own_fit", &options.min_score_of_own_fit);
  options.fast_correlative_scan_matcher = mapping::ParseFastCorrelativeScanMatcherOptions2D(
      reader.Child("fast_correlative_scan_matcher"));
  if (reader.Has("ceres_scan_matcher")) {
    options.ceres_scan_matcher =
        mapping::ParseCeresScanMatcherOptions2D(reader.Child("ceres_scan_matcher"));
  }
  reader.CheckOptions(options);
  return options;
}

namespace {

// How far a match moves the node from the estimate (the turn is bounded by the search window).
double CorrectionM(const common::Rigid2d& T_submap_node_estimate,
                   const common::Rigid2d& T_submap_node_match) {
  return (T_submap_node_match.translation() - T_submap_node_estimate.translation()).norm();
}

}  // namespace

bool DriftExplainsCorrection(const common::Rigid2d& T_submap_node_estimate,
                             const common::Rigid2d& T_submap_node_match, double path_m,
                             const ConstraintBuilderOptions2D& options) {
  if (options.max_correction_m == 0.0) return true;
  return CorrectionM(T_submap_node_estimate, T_submap_node_match) <=
         options.max_correction_m + options.max_correction_per_path_m * path_m;
}

double LoopSearchWindowM(double path_m, const ConstraintBuilderOptions2D& options) {
  const double fixed_m = options.fast_correlative_scan_matcher.linear_search_window_m;
  if (options.max_correction_m == 0.0) return fixed_m;
  return std::clamp(options.max_correction_m + options.max_correction_per_path_m * path_m, fixed_m,
                    options.max_linear_search_window_m);
}

bool EvidenceSupportsCorrection(const common::Rigid2d& T_submap_node_estimate,
                                const common::Rigid2d& T_submap_node_match, double evidence_z,
                                const ConstraintBuilderOptions2D& options) {
  if (options.min_correction_evidence_z == 0.0) return true;
  return CorrectionM(T_submap_node_estimate, T_submap_node_match) <=
             options.max_unevidenced_correction_m ||
         evidence_z >= options.min_correction_evidence_z;
}

double MinScoreForOwnFit(double own_fit, const ConstraintBuilderOptions2D& options) {
  const double min_score = options.fast_correlative_scan_matcher.min_score;
  // A submap whose own scans would not pass min_score is too blurred (local SLAM failed while
  // building it) to close loops against on a lower threshold.
  if (!(own_fit >= min_score) || options.min_score_of_own_fit == 0.0) return min_score;
  return std::min(min_score, options.min_score_of_own_fit * own_fit);
}

LoopClosureMatcher2D::LoopClosureMatcher2D(std::shared_ptr<const mapping::Submap2D> submap,
                                           const ConstraintBuilderOptions2D& options)
    : submap_(std::move(submap)),
      options_(options),
      // The grid (inflated if the submap is compacted) is let go once the precomputation grids
      // are built: they copy what they need.
      fast_matcher_(*submap_->grid(), options.fast_correlative_scan_matcher),
      ceres_matcher_(options.ceres_scan_matcher) {}

double LoopClosureMatcher2D::ScoreAt(const common::Rigid2d& T_submap_node,
                                     const sensor::PointCloud2d& cloud) const {
  return fast_matcher_.ScoreAt(submap_->T_local_submap() * T_submap_node, cloud);
}

std::optional<Constraint2D> LoopClosureMatcher2D::Match(
    const common::Rigid2d& T_submap_node_estimate, const sensor::PointCloud2d& cloud,
    double min_score, double* score, double path_m) const {
  *score = 0.0;
  if (cloud.empty()) return std::nullopt;
  // Submap grids live in the local SLAM frame; T_local_submap takes submap to grid coordinates.
  const common::Rigid2d T_grid_submap = submap_->T_local_submap();
  const common::Rigid2d initial = T_grid_submap * T_submap_node_estimate;
  common::Rigid2d T_grid_node;
  if (!fast_matcher_.MatchInWindow(initial, LoopSearchWindowM(path_m, options_), cloud, min_score,
                                   score, &T_grid_node)) {
    return std::nullopt;
  }
  // Only matches that pass min_score are refined, a small fraction of the searches: they
  // inflate the grid of a compacted submap (a millisecond for an office's), so that matchers
  // held within matcher_memory_budget_mb need not keep a copy of it.
  const std::shared_ptr<const mapping::ProbabilityGrid> grid = submap_->grid();
  common::Rigid2d refined;
  ceres::Solver::Summary summary;
  ceres_matcher_.Match(T_grid_node.translation(), T_grid_node, cloud, *grid, &refined,
                       &summary);
  Constraint2D constraint;
  constraint.T_submap_node = T_grid_submap.inverse() * refined;
  // Where the scan holds the match in one direction only (a corridor of plain walls), the
  // score was as high anywhere along the other: the constraint measures nothing there, and
  // keeps the estimate's translation along it so that loops.tsv shows no invented slide. Only
  // the structure the submap holds where the match put the scan counts: a scan at a corner
  // whose submap saw just one of the corridors slides along that one (simulator corridor: node
  // 863 matched 1.63 m along the south corridor into submap 0, which never saw the west one).
  if (options_.min_translation_information_ratio > 0.0) {
    const mapping::ScanInformation2D information = mapping::ComputeMatchedScanInformation2D(
        *grid, refined, cloud, mapping::kConfirmingProbability);
    if (information.TranslationRatio() < options_.min_translation_information_ratio) {
      // Round a curved wall the slide is an arc: the node turns with it.
      const double turn_rad_per_m = information.weakest_turn_rad_per_m;
      const Eigen::Vector2d along_in_submap =
          constraint.T_submap_node.rotation() * information.weakest_direction;
      const double slide_m = along_in_submap.dot(T_submap_node_estimate.translation() -
                                                 constraint.T_submap_node.translation());
      constraint.T_submap_node =
          constraint.T_submap_node *
          ArcMotion2D(slide_m * information.weakest_direction, slide_m * turn_rad_per_m);
      constraint.unmeasured_direction = information.weakest_direction;
      constraint.unmeasured_turn_rad_per_m = turn_rad_per_m;
    }
  }
  // Against the estimate, on the grid as the loop-closure Ceres match reads it (never-observed
  // cells are evidence against a pose).
  constraint.evidence_z =
      mapping::GainInStandardErrors(*grid, mapping::kMinProbability, initial,
                                    T_grid_submap * constraint.T_submap_node, cloud);
  constraint.translation_weight = options_.loop_closure_translation_weight;
  constraint.rotation_weight = options_.loop_closure_rotation_weight;
  constraint.tag = Constraint2D::kInterSubmap;
  return constraint;
}

}  // namespace pose_graph
}  // namespace fusemap
