#ifndef FUSEMAP_POSE_GRAPH_OVERLAPPING_SUBMAPS_TRIMMER_2D_H_
#define FUSEMAP_POSE_GRAPH_OVERLAPPING_SUBMAPS_TRIMMER_2D_H_

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "fusemap/common/config_reader.h"
#include "fusemap/common/rigid_transform.h"
#include "fusemap/mapping/probability_grid.h"

namespace fusemap {
namespace pose_graph {

// Lifelong mapping (Cartographer's overlapping submaps trimmer): a robot that keeps driving
// through a mapped building adds submaps forever. Old submaps whose area newer ones cover again
// are dropped, with the nodes that lived only in them, so memory and optimisation time follow
// the size of the building, not the length of the run.
struct OverlappingSubmapsTrimmerOptions2D {
  static constexpr int kMaxFreshSubmaps = 4;
  // Per map cell, the newest this many finished submaps that know it are kept; 0 disables
  // trimming.
  int fresh_submaps_count = 0;
  // A submap knows a cell once the cell's probability is at least this far from 0.5 (0.1:
  // about 3 hits or 10 misses with the default hit/miss probabilities). Cells a ray crossed
  // once or twice, through a doorway at an angle no later pass repeats, would otherwise keep
  // every pass's submaps alive (intel played 12 times: 82 finished submaps held, not 20-35).
  // 0 counts every known cell (Cartographer's rule).
  double min_probability_margin = 0.1;
  // A finished submap survives while it is among the fresh ones on at least this area.
  double min_covered_area_m2 = 2.0;
  // Trimming runs after an optimisation once this many submaps have finished since it last ran.
  int min_added_submaps_count = 5;

  bool enabled() const { return fresh_submaps_count > 0; }
  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

// Keys: fresh_submaps_count, min_probability_margin, min_covered_area_m2,
// min_added_submaps_count.
OverlappingSubmapsTrimmerOptions2D ParseOverlappingSubmapsTrimmerOptions2D(
    common::ConfigReader& reader);

// A finished submap as the trimmer sees it: its grid placed in the map frame. The grid is
// fetched when its turn comes and let go after (a compacted submap inflates a copy), so
// trimming holds one inflated grid at a time.
struct PlacedSubmap2D {
  int submap = 0;  // pose-graph index; a larger index is a newer submap
  common::Rigid2d T_map_grid;
  std::function<std::shared_ptr<const mapping::ProbabilityGrid>()> grid;
};

// The submaps to drop, in increasing index order. The cells each grid knows (beyond
// min_probability_margin) are binned into map cells of the newest grid's resolution; each map
// cell keeps its fresh_submaps_count newest submaps, and a submap kept on less than
// min_covered_area_m2 is returned. `submaps` must be sorted by increasing index and `options`
// enabled and valid (asserted).
std::vector<int> FindSubmapsToTrim(const std::vector<PlacedSubmap2D>& submaps,
                                   const OverlappingSubmapsTrimmerOptions2D& options);

}  // namespace pose_graph
}  // namespace fusemap

#endif  // FUSEMAP_POSE_GRAPH_OVERLAPPING_SUBMAPS_TRIMMER_2D_H_
