#ifndef FUSEMAP_MAPPING_SCAN_MATCHING_OCCUPIED_SPACE_COST_FUNCTION_2D_H_
#define FUSEMAP_MAPPING_SCAN_MATCHING_OCCUPIED_SPACE_COST_FUNCTION_2D_H_

#include <ceres/cost_function.h>

#include "fusemap/mapping/probability_grid.h"
#include "fusemap/sensor/sensor_types.h"

namespace fusemap {
namespace mapping {

// Residuals scaling_factor * (1 - M_smooth(T * p_i)), one per point of `cloud`, over the pose
// parameter block [x_m, y_m, angle_rad] = T_grid_tracking (Hess et al. 2016, eq. 8). M_smooth
// is the bicubic interpolation of the cell probabilities, cell centres being the samples;
// in never-observed cells and outside the grid the probability is `unknown_probability`
// (kMinProbability reads the grid as it is). The returned cost function refers to
// `cloud` and `grid`, which must outlive it; the caller (usually a ceres::Problem) owns it.
ceres::CostFunction* CreateOccupiedSpaceCostFunction2D(double scaling_factor,
                                                       const sensor::PointCloud2d& cloud,
                                                       const ProbabilityGrid& grid,
                                                       float unknown_probability);

}  // namespace mapping
}  // namespace fusemap

#endif  // FUSEMAP_MAPPING_SCAN_MATCHING_OCCUPIED_SPACE_COST_FUNCTION_2D_H_
