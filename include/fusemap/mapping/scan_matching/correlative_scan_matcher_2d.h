#ifndef FUSEMAP_MAPPING_SCAN_MATCHING_CORRELATIVE_SCAN_MATCHER_2D_H_
#define FUSEMAP_MAPPING_SCAN_MATCHING_CORRELATIVE_SCAN_MATCHER_2D_H_

#include <Eigen/Core>
#include <vector>

#include "fusemap/mapping/map_limits.h"
#include "fusemap/sensor/sensor_types.h"

namespace fusemap {
namespace mapping {

// Grid cells hit by the points of one rotated scan placed at the search centre.
using DiscreteScan2D = std::vector<Eigen::Array2i>;

// The candidate set of a correlative scan matcher (Olson 2009): angles
// centre + (i - num_angular_perturbations) * angular_step_rad for scan index i in
// [0, num_scans), and per angle the integer cell offsets in linear_bounds[i].
struct SearchParameters {
  struct LinearBounds {
    int min_x;
    int max_x;
    int min_y;
    int max_y;
  };

  // The angular step is chosen so that the farthest point of `cloud` moves by at most one
  // cell between neighbouring angles (Hess et al. 2016, eq. 7).
  SearchParameters(double linear_search_window_m, double angular_search_window_rad,
                   const sensor::PointCloud2d& cloud, double resolution_m);
  SearchParameters(int num_linear_perturbations, int num_angular_perturbations,
                   double angular_step_rad, double resolution_m);

  // Drops offsets that would move a scan's bounding box completely off the grid.
  void ShrinkToFit(const std::vector<DiscreteScan2D>& scans, const MapLimits& limits);

  int num_angular_perturbations;
  double angular_step_rad;
  double resolution_m;
  int num_scans;
  std::vector<LinearBounds> linear_bounds;  // one per scan index
};

// Angular step for a scan whose farthest point is `max_range_m` away (Hess et al. 2016, eq. 7).
double ComputeAngularStep(double max_range_m, double resolution_m);

// The cloud rotated to every candidate angle (relative to the search centre's angle), in
// scan-index order.
std::vector<sensor::PointCloud2d> GenerateRotatedScans(const sensor::PointCloud2d& cloud,
                                                       const SearchParameters& params);

// Each rotated scan translated by `initial_translation` and mapped to cell indices.
std::vector<DiscreteScan2D> DiscretizeScans(const MapLimits& limits,
                                            const std::vector<sensor::PointCloud2d>& scans,
                                            const Eigen::Vector2f& initial_translation);

// One candidate pose, relative to the search centre: rotated scan `scan_index` shifted by
// (x_offset_cells, y_offset_cells).
struct Candidate2D {
  Candidate2D(int scan_index, int x_offset_cells, int y_offset_cells,
              const SearchParameters& params)
      : scan_index(scan_index),
        x_offset_cells(x_offset_cells),
        y_offset_cells(y_offset_cells),
        x_m(x_offset_cells * params.resolution_m),
        y_m(y_offset_cells * params.resolution_m),
        angle_rad((scan_index - params.num_angular_perturbations) * params.angular_step_rad) {}

  int scan_index;
  int x_offset_cells;
  int y_offset_cells;
  double x_m;
  double y_m;
  double angle_rad;
  double score = 0.0;
  // The score without a search's prior on the distance from its centre (see
  // FastCorrelativeScanMatcherOptions2D): equal to `score` where there is none.
  double fit = 0.0;

  bool operator<(const Candidate2D& other) const { return score < other.score; }
  bool operator>(const Candidate2D& other) const { return score > other.score; }
};

}  // namespace mapping
}  // namespace fusemap

#endif  // FUSEMAP_MAPPING_SCAN_MATCHING_CORRELATIVE_SCAN_MATCHER_2D_H_
