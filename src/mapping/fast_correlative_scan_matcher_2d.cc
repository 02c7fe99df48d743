#include "fusemap/mapping/scan_matching/fast_correlative_scan_matcher_2d.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>

namespace fusemap {
namespace mapping {
namespace {

// No upper limit on the fit of the leaves a search looks for.
constexpr double kNoMaxFit = 2.0;  // above any score

}  // namespace

void FastCorrelativeScanMatcherOptions2D::Check(common::OptionChecker* check) const {
  check->Require(linear_search_window_m >= 0.0, "linear_search_window_m", "must be >= 0");
  check->Require(angular_search_window_rad >= 0.0 && angular_search_window_rad <= common::kPi,
                 "angular_search_window_rad", "must be in [0, pi]");
  check->Require(branch_and_bound_depth >= 1 && branch_and_bound_depth <= 15,
                 "branch_and_bound_depth", "must be in [1, 15]");
  check->Require(min_score >= 0.0 && min_score <= 1.0, "min_score", "must be in [0, 1]");
  check->Require(translation_delta_cost_weight >= 0.0, "translation_delta_cost_weight",
                 "must be >= 0");
  check->Require(rotation_delta_cost_weight >= 0.0, "rotation_delta_cost_weight", "must be >= 0");
}

bool FastCorrelativeScanMatcherOptions2D::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

FastCorrelativeScanMatcherOptions2D ParseFastCorrelativeScanMatcherOptions2D(
    common::ConfigReader& reader) {
  FastCorrelativeScanMatcherOptions2D options;
  reader.Get("linear_search_window_m", &options.linear_search_window_m);
  reader.Get("angular_search_window_rad", &options.angular_search_window_rad);
  reader.Get("branch_and_bound_depth", &options.branch_and_bound_depth);
  reader.Get("min_score", &options.min_score);
  reader.Get("translation_delta_cost_weight", &options.translation_delta_cost_weight);
  reader.Get("rotation_delta_cost_weight", &options.rotation_delta_cost_weight);
  reader.CheckOptions(options);
  return options;
}

FastCorrelativeScanMatcher2D::FastCorrelativeScanMatcher2D(
    const ProbabilityGrid& grid, const FastCorrelativeScanMatcherOptions2D& options,
    PrecomputationBuffers* buffers)
    : FastCorrelativeScanMatcher2D(
          grid.limits(), PrecomputationGridStack2D(grid, options.branch_and_bound_depth, buffers),
          options) {}

FastCorrelativeScanMatcher2D::FastCorrelativeScanMatcher2D(
    const MapLimits& limits, PrecomputationGridStack2D grids,
    const FastCorrelativeScanMatcherOptions2D& options)
    : limits_(limits), options_(options), grids_(std::move(grids)) {
  std::string error;
  assert(options_.IsValid(&error));
  assert(grids_.max_depth() == options_.branch_and_bound_depth);
  (void)error;
}

bool FastCorrelativeScanMatcher2D::Match(const common::Rigid2d& initial_pose,
                                         const sensor::PointCloud2d& cloud, double min_score,
                                         double* score, common::Rigid2d* pose) const {
  return MatchInWindow(initial_pose, options_.linear_search_window_m, cloud, min_score, score,
                       pose);
}

bool FastCorrelativeScanMatcher2D::MatchInWindow(const common::Rigid2d& initial_pose,
                                                 double linear_search_window_m,
                                                 const sensor::PointCloud2d& cloud,
                                                 double min_score, double* score,
                                                 common::Rigid2d* pose) const {
  const SearchParameters params(linear_search_window_m, options_.angular_search_window_rad, cloud,
                                limits_.resolution_m);
  const bool with_prior =
      options_.translation_delta_cost_weight > 0.0 || options_.rotation_delta_cost_weight > 0.0;
  return MatchWithSearchParameters(params, initial_pose, cloud, min_score, with_prior, score,
                                   pose);
}

double FastCorrelativeScanMatcher2D::ScoreAt(const common::Rigid2d& pose,
                                             const sensor::PointCloud2d& cloud) const {
  if (cloud.empty()) return 0.0;
  const Eigen::Matrix2f rotation =
      Eigen::Rotation2Df(static_cast<float>(pose.angle_rad())).matrix();
  const Eigen::Vector2f translation = pose.translation().cast<float>();
  const PrecomputationGrid2D& grid = grids_.Get(0);
  long value_sum = 0;
  for (const Eigen::Vector2f& point : cloud) {
    value_sum += grid.GetValue(limits_.GetCellIndex(rotation * point + translation));
  }
  return PrecomputationScore(value_sum, static_cast<int>(cloud.size()));
}

bool FastCorrelativeScanMatcher2D::MatchFullSubmap(const sensor::PointCloud2d& cloud,
                                                   double min_score, double* score,
                                                   common::Rigid2d* pose) const {
  // A window far larger than the grid; ShrinkToFit then cuts it down to the grid.
  const double grid_extent_m =
      limits_.resolution_m * std::max(limits_.num_x_cells, limits_.num_y_cells);
  const SearchParameters params(2.0 * grid_extent_m, common::kPi, cloud, limits_.resolution_m);
  const common::Rigid2d centre = common::Rigid2d::Translation(
      limits_.origin_m +
      0.5 * limits_.resolution_m * Eigen::Vector2d(limits_.num_x_cells, limits_.num_y_cells));
  return MatchWithSearchParameters(params, centre, cloud, min_score, false, score, pose);
}

bool FastCorrelativeScanMatcher2D::MatchWithSearchParameters(
    SearchParameters params, const common::Rigid2d& initial_pose,
    const sensor::PointCloud2d& cloud, double min_score, bool with_prior, double* score,
    common::Rigid2d* pose) const {
  assert(score != nullptr && pose != nullptr);
  if (cloud.empty()) return false;
  const Eigen::Matrix2f rotation =
      Eigen::Rotation2Df(static_cast<float>(initial_pose.angle_rad())).matrix();
  sensor::PointCloud2d rotated_cloud;
  rotated_cloud.reserve(cloud.size());
  for (const Eigen::Vector2f& point : cloud) rotated_cloud.push_back(rotation * point);
  ScanSet scans;
  scans.scans = DiscretizeScans(limits_, GenerateRotatedScans(rotated_cloud, params),
                                initial_pose.translation().cast<float>());
  params.ShrinkToFit(scans.scans, limits_);
  for (const DiscreteScan2D& scan : scans.scans) {
    Eigen::Array2i min_cell = Eigen::Array2i::Zero();
    Eigen::Array2i max_cell = Eigen::Array2i::Zero();
    if (!scan.empty()) min_cell = max_cell = scan.front();
    for (const Eigen::Array2i& cell : scan) {
      min_cell = min_cell.min(cell);
      max_cell = max_cell.max(cell);
    }
    scans.min_cells.push_back(min_cell);
    scans.max_cells.push_back(max_cell);
  }

  const std::vector<Candidate2D> lowest_resolution_candidates =
      ComputeLowestResolutionCandidates(scans, params, with_prior);
  // With a prior, the threshold is on the match itself: the prior only chooses among matches,
  // so a good match far from the centre is not rejected for being far. The answer is the
  // candidate the prior ranks first, and none if its own score does not beat min_score. That
  // is searched in two steps, each pruning more than one search for the first-ranked candidate
  // could: the first-ranked among those that beat min_score (subtrees whose scores cannot are
  // skipped, however well the prior ranks them); then, only if there is one, whether a
  // candidate that does not beat min_score is ranked above it (then that one would be the
  // answer; none that beats min_score can be). Most of local SLAM's wide searches end after the
  // first step with nothing found, their caller having asked for a score that would change its
  // answer. Without a prior the first step is the whole search.
  std::vector<std::vector<Candidate2D>> children_by_depth(grids_.max_depth());
  const Candidate2D best = BranchAndBound(scans, params, lowest_resolution_candidates,
                                          grids_.max_depth(), with_prior ? 0.0 : min_score,
                                          min_score, kNoMaxFit, with_prior, &children_by_depth);
  if (with_prior && best.fit > min_score) {
    const Candidate2D ranked_above =
        BranchAndBound(scans, params, lowest_resolution_candidates, grids_.max_depth(), best.score,
                       -1.0, min_score, with_prior, &children_by_depth);
    if (ranked_above.score > best.score) return false;
  }
  if (!(best.fit > min_score)) return false;
  *score = best.fit;
  *pose = common::Rigid2d(initial_pose.translation() + Eigen::Vector2d(best.x_m, best.y_m),
                          initial_pose.angle_rad() + best.angle_rad);
  return true;
}

std::vector<Candidate2D> FastCorrelativeScanMatcher2D::ComputeLowestResolutionCandidates(
    const ScanSet& scans, const SearchParameters& params, bool with_prior) const {
  const PrecomputationGrid2D& grid = grids_.Get(grids_.max_depth());
  const int step = grid.width_cells();
  // Offsets min, min + step, ... up to max along one axis.
  const auto num_offsets = [step](int min, int max) { return (max - min) / step + 1; };
  std::vector<Candidate2D> candidates;
  size_t count = 0;
  for (const SearchParameters::LinearBounds& bounds : params.linear_bounds) {
    if (bounds.max_x < bounds.min_x || bounds.max_y < bounds.min_y) continue;
    count += static_cast<size_t>(num_offsets(bounds.min_x, bounds.max_x)) *
             num_offsets(bounds.min_y, bounds.max_y);
  }
  candidates.reserve(count);  // thousands per local SLAM wide search
  std::vector<long> sums;
  for (int i = 0; i < params.num_scans; ++i) {
    const SearchParameters::LinearBounds& bounds = params.linear_bounds[i];
    if (bounds.max_x < bounds.min_x || bounds.max_y < bounds.min_y) continue;
    const int num_x = num_offsets(bounds.min_x, bounds.max_x);
    const int num_y = num_offsets(bounds.min_y, bounds.max_y);
    sums.resize(static_cast<size_t>(num_x) * num_y);
    AppendScoredLattice(grid, scans, i, Eigen::Array2i(bounds.min_x, bounds.min_y), step, num_x,
                        num_y, params, with_prior, sums.data(), &candidates);
  }
  std::sort(candidates.begin(), candidates.end(), std::greater<Candidate2D>());
  return candidates;
}

void FastCorrelativeScanMatcher2D::AppendScoredLattice(
    const PrecomputationGrid2D& grid, const ScanSet& scans, int scan_index,
    const Eigen::Array2i& first, int step, int num_x, int num_y, const SearchParameters& params,
    bool with_prior, long* sums, std::vector<Candidate2D>* candidates) const {
  const int i = scan_index;
  grid.SumValuesOverOffsets(scans.scans[i], scans.min_cells[i], scans.max_cells[i], first, step,
                            num_x, num_y, sums);
  const int num_points = static_cast<int>(scans.scans[i].size());
  for (int xi = 0; xi < num_x; ++xi) {
    for (int yi = 0; yi < num_y; ++yi) {
      candidates->emplace_back(i, first.x() + xi * step, first.y() + yi * step, params);
      SetScore(grid, sums[static_cast<size_t>(xi) * num_y + yi], num_points, with_prior,
               &candidates->back());
    }
  }
}

void FastCorrelativeScanMatcher2D::SetScore(const PrecomputationGrid2D& grid, long value_sum,
                                            int num_points, bool with_prior,
                                            Candidate2D* candidate) const {
  candidate->score = PrecomputationScore(value_sum, num_points);
  candidate->fit = candidate->score;
  if (!with_prior) return;
  // Offset of the cell in [start, start + width) nearest to 0.
  const auto nearest_cells = [](int start, int width) {
    return start > 0 ? start : (start + width - 1 < 0 ? start + width - 1 : 0);
  };
  // The candidate stands for the offsets [x, x + width) x [y, y + width); the prior is
  // largest at the one nearest the centre, so score times that factor still bounds every
  // leaf below it and the search stays exact.
  const int width = grid.width_cells();
  // sqrt of the exact integer sum, not std::hypot: the same distance (correctly rounded)
  // at a fraction of the cost, and this runs for every candidate of local SLAM's wide search.
  const long nx = nearest_cells(candidate->x_offset_cells, width);
  const long ny = nearest_cells(candidate->y_offset_cells, width);
  const double distance_m =
      limits_.resolution_m * std::sqrt(static_cast<double>(nx * nx + ny * ny));
  const double cost = distance_m * options_.translation_delta_cost_weight +
                      std::abs(candidate->angle_rad) * options_.rotation_delta_cost_weight;
  candidate->score *= std::exp(-cost * cost);
}

// Depth-first branch and bound (Hess et al. 2016, Algorithm 3). A candidate at depth d covers
// the offsets [x, x + 2^d) x [y, y + 2^d) of its scan, and its depth-d score bounds theirs
// (eq. 14), so a subtree whose bound does not beat the best leaf found so far is skipped.
Candidate2D FastCorrelativeScanMatcher2D::BranchAndBound(
    const ScanSet& scans, const SearchParameters& params,
    const std::vector<Candidate2D>& candidates, int depth, double min_score, double min_fit,
    double max_fit, bool with_prior,
    std::vector<std::vector<Candidate2D>>* children_by_depth) const {
  Candidate2D none(0, 0, 0, params);
  none.score = -1.0;
  none.fit = -1.0;
  if (depth == 0) {
    // Sorted best first: the first whose fit is in range (without a prior, fit is score).
    for (const Candidate2D& candidate : candidates) {
      if (candidate.fit > min_fit && candidate.fit <= max_fit) return candidate;
    }
    return none;
  }
  Candidate2D best = none;
  best.score = min_score;
  const int half_width = 1 << (depth - 1);
  for (const Candidate2D& candidate : candidates) {
    if (candidate.score <= best.score) break;
    // A candidate's fit bounds its leaves' as its score does theirs.
    if (candidate.fit <= min_fit) continue;
    // Leaves that fit at most max_fit score at most that times the prior's factor.
    if (candidate.fit > max_fit && candidate.score * (max_fit / candidate.fit) <= best.score) {
      continue;
    }
    const SearchParameters::LinearBounds& bounds = params.linear_bounds[candidate.scan_index];
    // Reused storage: thousands of candidates are expanded per search.
    std::vector<Candidate2D>& children = (*children_by_depth)[depth - 1];
    children.clear();
    // The children at {x, x + half_width} x {y, y + half_width} that lie in the window.
    const int num_x = candidate.x_offset_cells + half_width <= bounds.max_x ? 2 : 1;
    const int num_y = candidate.y_offset_cells + half_width <= bounds.max_y ? 2 : 1;
    long sums[4];
    AppendScoredLattice(grids_.Get(depth - 1), scans, candidate.scan_index,
                        Eigen::Array2i(candidate.x_offset_cells, candidate.y_offset_cells),
                        half_width, num_x, num_y, params, with_prior, sums, &children);
    std::sort(children.begin(), children.end(), std::greater<Candidate2D>());
    const Candidate2D child_best = BranchAndBound(scans, params, children, depth - 1, best.score,
                                                  min_fit, max_fit, with_prior, children_by_depth);
    if (child_best.score > best.score) best = child_best;
  }
  return best;
}

CellBox CellsReadByMatch(const MapLimits& limits,
                         const FastCorrelativeScanMatcherOptions2D& options,
                         const common::Rigid2d& initial_pose, const sensor::PointCloud2d& cloud) {
  if (cloud.empty()) return CellBox{};
  // The search's own angles (its step depends on the cloud) and offsets.
  const SearchParameters params(options.linear_search_window_m, options.angular_search_window_rad,
                                cloud, limits.resolution_m);
  const double max_angle_rad = params.num_angular_perturbations * params.angular_step_rad;
  const int num_linear = params.linear_bounds.front().max_x;
  // Each point's arc through the window, at kSamples + 1 angles: between two of them it strays
  // from their chord, and so from the box of its ends, by at most r (1 - cos(step / 2)).
  constexpr int kSamples = 16;
  const double sample_step_rad = 2.0 * max_angle_rad / kSamples;
  double max_range_m = 0.0;
  for (const Eigen::Vector2f& point : cloud) {
    max_range_m = std::max(max_range_m, point.cast<double>().norm());
  }
  const double sagitta_m = max_range_m * (1.0 - std::cos(0.5 * sample_step_rad));
  Eigen::Vector2d min_m = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d max_m = -min_m;
  for (int k = 0; k <= kSamples; ++k) {
    const Eigen::Matrix2d rotation =
        Eigen::Rotation2Dd(initial_pose.angle_rad() - max_angle_rad + k * sample_step_rad).matrix();
    for (const Eigen::Vector2f& point : cloud) {
      const Eigen::Vector2d moved_m = rotation * point.cast<double>() + initial_pose.translation();
      min_m = min_m.cwiseMin(moved_m);
      max_m = max_m.cwiseMax(moved_m);
    }
  }
  const Eigen::Vector2d pad_m = Eigen::Vector2d::Constant(sagitta_m);
  // One cell more each way: the search rotates and rounds in float.
  const Eigen::Array2i min_cell =
      limits.GetCellIndex((min_m - pad_m).cast<float>()) - (num_linear + 1);
  const Eigen::Array2i max_cell =
      limits.GetCellIndex((max_m + pad_m).cast<float>()) + (num_linear + 1);
  return CellBox{min_cell, max_cell.x() - min_cell.x() + 1, max_cell.y() - min_cell.y() + 1};
}

}  // namespace mapping
}  // namespace fusemap
