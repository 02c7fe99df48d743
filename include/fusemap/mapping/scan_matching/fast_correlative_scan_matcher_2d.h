#ifndef FUSEMAP_MAPPING_SCAN_MATCHING_FAST_CORRELATIVE_SCAN_MATCHER_2D_H_
#define FUSEMAP_MAPPING_SCAN_MATCHING_FAST_CORRELATIVE_SCAN_MATCHER_2D_H_

#include <string>
#include <vector>

#include "fusemap/common/config_reader.h"
#include "fusemap/common/math.h"
#include "fusemap/common/rigid_transform.h"
#include "fusemap/mapping/map_limits.h"
#include "fusemap/mapping/probability_grid.h"
#include "fusemap/mapping/scan_matching/correlative_scan_matcher_2d.h"
#include "fusemap/mapping/scan_matching/precomputation_grid_2d.h"
#include "fusemap/sensor/sensor_types.h"

namespace fusemap {
namespace mapping {

struct FastCorrelativeScanMatcherOptions2D {
  // Loop closure's window around where the graph puts a node (config/default.yaml).
  double linear_search_window_m = 4.0;
  double angular_search_window_rad = 0.35;
  int branch_and_bound_depth = 7;
  // The threshold callers (the constraint builder) pass to Match for local searches.
  double min_score = 0.55;
  // Prior on the search centre for Match (not MatchFullSubmap), as in the real-time
  // correlative matcher: the search maximises score * exp(-(w_t * d_m + w_r * |a_rad|)^2) for
  // a candidate's offset d_m and turn a_rad from the centre. min_score and the score returned
  // are the chosen candidate's own score, without the prior: the answer is the candidate with
  // the best score times prior, and there is none if its own score does not beat min_score.
  // 0 and 0 (the defaults) search as without a prior.
  double translation_delta_cost_weight = 0.0;
  double rotation_delta_cost_weight = 0.0;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

FastCorrelativeScanMatcherOptions2D ParseFastCorrelativeScanMatcherOptions2D(
    common::ConfigReader& reader);

// Loop-closure scan matcher over one finished grid (Hess et al. 2016, Sec. V): depth-first
// branch and bound over the same candidates an exhaustive correlative search would score,
// bounded by the precomputation grids. The result is exactly the best of those candidates
// (scores as quantised by precomputation_grid_2d.h). Holds no reference to the grid.
class FastCorrelativeScanMatcher2D {
 public:
  // With `buffers`, the precomputation grids are built in their storage (see
  // PrecomputationGridStack2D).
  FastCorrelativeScanMatcher2D(const ProbabilityGrid& grid,
                               const FastCorrelativeScanMatcherOptions2D& options,
                               PrecomputationBuffers* buffers = nullptr);
  // Over precomputation grids built by the caller, whose cell 0 is `limits`' cell 0.
  FastCorrelativeScanMatcher2D(const MapLimits& limits, PrecomputationGridStack2D grids,
                               const FastCorrelativeScanMatcherOptions2D& options);

  FastCorrelativeScanMatcher2D(const FastCorrelativeScanMatcher2D&) = delete;
  FastCorrelativeScanMatcher2D& operator=(const FastCorrelativeScanMatcher2D&) = delete;

  // Searches the option windows around `initial_pose` (T_grid_tracking) for `cloud` (tracking
  // frame). Returns true and fills *score and *pose if the best score exceeds `min_score`.
  bool Match(const common::Rigid2d& initial_pose, const sensor::PointCloud2d& cloud,
             double min_score, double* score, common::Rigid2d* pose) const;
  // As Match, with `linear_search_window_m` in place of the option's.
  bool MatchInWindow(const common::Rigid2d& initial_pose, double linear_search_window_m,
                     const sensor::PointCloud2d& cloud, double min_score, double* score,
                     common::Rigid2d* pose) const;

  // The score Match gives `cloud` (tracking frame) at `pose` (T_grid_tracking) itself, with
  // no search: the mean quantised probability of the cells its points fall in (0 off the grid).
  double ScoreAt(const common::Rigid2d& pose, const sensor::PointCloud2d& cloud) const;

  // Searches every translation over the grid and every angle in [-pi, pi].
  bool MatchFullSubmap(const sensor::PointCloud2d& cloud, double min_score, double* score,
                       common::Rigid2d* pose) const;

  const PrecomputationGridStack2D& precomputation_grids() const { return grids_; }
  // Hands the precomputation grids' storage to `buffers` for a rebuilt matcher; this one must
  // not match afterwards.
  void ReleaseGridsInto(PrecomputationBuffers* buffers) { grids_.ReleaseInto(buffers); }

 private:
  // The rotated, discretised scans of one search, with each one's cell bounding box.
  struct ScanSet {
    std::vector<DiscreteScan2D> scans;
    std::vector<Eigen::Array2i> min_cells;
    std::vector<Eigen::Array2i> max_cells;
  };

  bool MatchWithSearchParameters(SearchParameters params, const common::Rigid2d& initial_pose,
                                 const sensor::PointCloud2d& cloud, double min_score,
                                 bool with_prior, double* score, common::Rigid2d* pose) const;
  std::vector<Candidate2D> ComputeLowestResolutionCandidates(const ScanSet& scans,
                                                             const SearchParameters& params,
                                                             bool with_prior) const;
  // Appends scan_index's candidates at the offsets first + (xi * step, yi * step), xi in
  // [0, num_x), yi in [0, num_y), scored on `grid` (their sums into `sums`, num_x * num_y
  // long): the lowest-resolution lattice of a search and each expansion's children.
  void AppendScoredLattice(const PrecomputationGrid2D& grid, const ScanSet& scans, int scan_index,
                           const Eigen::Array2i& first, int step, int num_x, int num_y,
                           const SearchParameters& params, bool with_prior, long* sums,
                           std::vector<Candidate2D>* candidates) const;
  // The candidate's score from the sum of its points' values in `grid` (times the prior's
  // factor with `with_prior`).
  void SetScore(const PrecomputationGrid2D& grid, long value_sum, int num_points, bool with_prior,
                Candidate2D* candidate) const;
  // The first best leaf below `candidates` (sorted best first) whose score beats `min_score`
  // and whose fit is in (`min_fit`, `max_fit`]; if there is none, a candidate whose score does
  // not beat `min_score` and whose fit is -1. (*children_by_depth)[d] holds the children
  // scored at depth d (one expansion at a time).
  Candidate2D BranchAndBound(const ScanSet& scans, const SearchParameters& params,
                             const std::vector<Candidate2D>& candidates, int depth,
                             double min_score, double min_fit, double max_fit, bool with_prior,
                             std::vector<std::vector<Candidate2D>>* children_by_depth) const;

  MapLimits limits_;
  FastCorrelativeScanMatcherOptions2D options_;
  PrecomputationGridStack2D grids_;
};

// A box holding every cell of `limits` (the matcher's) that Match(initial_pose, cloud, ...)
// with `options` reads, at any depth: each point of `cloud` turned within the angular window
// and moved within the linear one, plus a cell for rounding. A matcher over a stack built for
// these cells only (PrecomputationGridStack2D's `reads`) answers as one over the whole grid.
CellBox CellsReadByMatch(const MapLimits& limits,
                         const FastCorrelativeScanMatcherOptions2D& options,
                         const common::Rigid2d& initial_pose, const sensor::PointCloud2d& cloud);

}  // namespace mapping
}  // namespace fusemap

#endif  // FUSEMAP_MAPPING_SCAN_MATCHING_FAST_CORRELATIVE_SCAN_MATCHER_2D_H_
