#ifndef FUSEMAP_MAPPING_SCAN_MATCHING_INITIAL_MATCH_2D_H_
#define FUSEMAP_MAPPING_SCAN_MATCHING_INITIAL_MATCH_2D_H_

#include <memory>
#include <string>

#include "fusemap/common/config_reader.h"
#include "fusemap/common/rigid_transform.h"
#include "fusemap/mapping/scan_matching/fast_correlative_scan_matcher_2d.h"
#include "fusemap/mapping/submap_2d.h"
#include "fusemap/sensor/sensor_types.h"

namespace fusemap {
namespace mapping {

struct InitialMatchOptions2D {
  // On by default, at the real-time window's edge only (only_at_window_edge).
  bool enabled = true;
  // Windows around the extrapolated pose, pyramid depth and the score below which the
  // extrapolated pose is kept.
  FastCorrelativeScanMatcherOptions2D fast_correlative_scan_matcher;
  // The search runs on the submap's grid max-pooled to about this cell size (0: the submap's
  // own). Sparse beams leave gaps between the cells they hit on far walls, which a fine grid
  // punishes; the coarse answer is within a cell, which the fine matchers then refine.
  double matching_resolution_m = 0.05;
  // The score of a point on a never-observed cell. The other matchers use kMinProbability,
  // which drags a scan that sees new space back into the mapped area (along a corridor: back
  // towards where it came from); nearer 0.5 treats unobserved space as no evidence either way.
  // Above kMinProbability, the grid is also padded by unknown_padding_m around the known area.
  float unknown_probability = 0.5f;
  // 2 m covers the default window; 30 m cost 3-4x the time for the same poses on csail.
  double unknown_padding_m = 2.0;
  // If > 0, the wide answer is used only if it scores this much above the best pose in the
  // near windows around the prediction; otherwise that nearer pose is used. Repeating
  // structure (doors along a corridor) scores alike at several offsets, and the nearer one is
  // the likelier.
  double min_score_gain = 0.0;
  double near_linear_search_window_m = 0.5;
  double near_angular_search_window_rad = 0.2;
  // The precomputation grids of the matching submap are rebuilt once it has had this many
  // insertions since they were built (and always when the matching submap changes, or a
  // search reads cells they were not built for: they cover the search's cells only). 1 keeps
  // the search against the current grid, so a builder restored from a checkpoint (which starts
  // with no grids) continues exactly; larger values trade that for less precomputation.
  int refresh_every_n_insertions = 1;
  // If true, the search runs only for a scan whose real-time correlative match landed on the
  // border of its small window (the prediction was further off than that window allows: a
  // sharp turn with poor odometry, a jump), and its answer is taken only if the real-time
  // match started from it scores at least min_rescore_gain above the plain one. Scans the
  // small window already explains cost nothing extra and are matched as without this stage.
  // Without use_online_correlative_scan_matching the stage then never runs.
  bool only_at_window_edge = true;
  double min_rescore_gain = 0.01;

  InitialMatchOptions2D();
  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

// Keys: enabled, matching_resolution_m, unknown_probability, unknown_padding_m, min_score_gain,
// near_linear_search_window_m, near_angular_search_window_rad, refresh_every_n_insertions,
// only_at_window_edge, min_rescore_gain,
// linear_search_window_m, angular_search_window_rad, branch_and_bound_depth, min_score,
// translation_delta_cost_weight, rotation_delta_cost_weight (the last six as in
// fast_correlative_scan_matcher; the prior is on the extrapolated pose).
InitialMatchOptions2D ParseInitialMatchOptions2D(common::ConfigReader& reader);

// `grid` coarsened by `factor` (>= 1) per axis, each coarse cell holding the most occupied of
// its known cells. Covers grid.Cropped() (the known area) plus `pad_cells` on every side; cells
// with nothing known get `unknown_probability` if that is above kMinProbability.
ProbabilityGrid MaxPoolGrid(const ProbabilityGrid& grid, int factor, float unknown_probability,
                            int pad_cells);

// A global-style first guess for local SLAM when the motion prior is poor (no odometry, large
// gaps between scans): branch and bound (Hess et al. 2016, Sec. V) over a large window around
// the extrapolated pose, against the submap local SLAM matches to. The fine matchers then
// start from its answer. The precomputation grids are a cache of the submap's grid only, so
// the object holds no state a checkpoint would need.
class InitialMatcher2D {
 public:
  explicit InitialMatcher2D(const InitialMatchOptions2D& options);

  InitialMatcher2D(const InitialMatcher2D&) = delete;
  InitialMatcher2D& operator=(const InitialMatcher2D&) = delete;

  // `predicted` and *pose are T_local_tracking (the submap's grid is in the local frame);
  // `cloud` is in the tracking frame. Returns true and fills *score and *pose if the best
  // candidate beats min_score and `min_fit`: a caller that would not take an answer scoring
  // less passes it, and the search prunes what cannot reach it. The answer, where there is
  // one, is the same as without it.
  bool Match(const std::shared_ptr<const Submap2D>& submap, const common::Rigid2d& predicted,
             const sensor::PointCloud2d& cloud, double* score, common::Rigid2d* pose,
             double min_fit = 0.0);

  // How often the precomputation grids were (re)built, for measurements.
  int num_precomputations() const { return num_precomputations_; }

 private:
  InitialMatchOptions2D options_;
  // Identifies the submap the grids were built from without keeping it alive (a new submap
  // could reuse a freed one's address).
  std::weak_ptr<const Submap2D> cached_submap_;
  int cached_num_range_data_ = 0;
  // The grids' layout, and the cells (of it) they were built for.
  MapLimits cached_limits_;
  CellBox cached_reads_;
  std::unique_ptr<FastCorrelativeScanMatcher2D> matcher_;
  std::unique_ptr<FastCorrelativeScanMatcher2D> local_matcher_;  // if min_score_gain > 0
  // The previous grids' storage, which each rebuild reuses.
  PrecomputationBuffers buffers_;
  int num_precomputations_ = 0;
};

}  // namespace mapping
}  // namespace fusemap

#endif  // FUSEMAP_MAPPING_SCAN_MATCHING_INITIAL_MATCH_2D_H_
