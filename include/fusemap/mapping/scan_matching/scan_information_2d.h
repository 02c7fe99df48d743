#ifndef FUSEMAP_MAPPING_SCAN_MATCHING_SCAN_INFORMATION_2D_H_
#define FUSEMAP_MAPPING_SCAN_MATCHING_SCAN_INFORMATION_2D_H_

#include <Eigen/Core>

#include "fusemap/common/rigid_transform.h"
#include "fusemap/mapping/probability_grid.h"
#include "fusemap/sensor/sensor_types.h"

namespace fusemap {
namespace mapping {

// How firmly a scan's own geometry can pin down a match of it, whatever map it is matched
// against: each point lying on a line of its neighbours (a wall) is held across that line, not
// along it, as in point-to-line ICP, and the Gauss-Newton information over the pose is the sum
// (Gelfand et al. 2003 for ICP; Zhang, Kaess & Singh 2016 call the smallest eigenvalue the
// problem's degeneracy). A scan of a corridor whose walls are two parallel lines holds the
// match across the corridor only: matched anywhere along it, it fits as well. Taken from the
// scan rather than from the map where the match put it, because a match slid to the wrong place
// lands its points on structure (a corner) the scan never saw.
struct ScanInformation2D {
  // Over [x_m, y_m, angle_rad] of the scan's pose, mean per point (unitless in translation).
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  // Eigenvalues of the translation information with the angle left free (the Schur complement
  // of the angle block); weakest_direction is a unit vector in the scan's frame.
  double weakest_translation = 0.0;
  double strongest_translation = 0.0;
  Eigen::Vector2d weakest_direction = Eigen::Vector2d::UnitX();
  // The turn that goes with a slide along weakest_direction at least cost, in rad per metre of
  // it: 0 along a straight corridor, about 1/r along a curved wall of radius r (a ring
  // corridor), where a match slides round the curve and turns with it. 0 unless turning takes
  // away nearly all that the slide costs without it (a straight corridor's door frames suggest
  // a small turn that explains little).
  double weakest_turn_rad_per_m = 0.0;
  // Points whose neighbours lie on a line, i.e. that contribute.
  int points_on_lines = 0;

  // weakest / strongest translation information, in [0, 1]: ~0 when a match can slide along one
  // direction (a corridor), up to 1 when walls hold it equally every way; 0 without any line.
  double TranslationRatio() const;
};

// `cloud` in the frame the pose rotates about (the tracking frame). A point's line is fitted to
// it and its 4 nearest neighbours within 2 m (sparse, voxel-filtered clouds included) and counts
// when they spread along one direction at least 10 times more than across it.
ScanInformation2D ComputeScanInformation2D(const sensor::PointCloud2d& cloud);

// The direction (in the cloud's frame) a match of `cloud` can slide along: the weakest
// direction when TranslationRatio() < min_ratio, else zero.
Eigen::Vector2d UnpinnedDirection2D(const sensor::PointCloud2d& cloud, double min_ratio);

// A cell more likely occupied than free confirms the scan point that lands on it.
constexpr float kConfirmingProbability = 0.5f;

// The same over the points the map confirms: those that land, at the matched pose T_grid_scan,
// on cells at least min_probability likely occupied (kConfirmingProbability). Structure the
// scan sees and the map does not hold (a side corridor the submap never saw) measures nothing
// in that match; a scan whose only confirmed structure is two parallel walls is a corridor
// scan whatever else it saw. Lines are fitted among all the scan's points, so that the map only
// removes structure, never adds it.
ScanInformation2D ComputeMatchedScanInformation2D(const ProbabilityGrid& grid,
                                                  const common::Rigid2d& T_grid_scan,
                                                  const sensor::PointCloud2d& cloud,
                                                  float min_probability);

}  // namespace mapping
}  // namespace fusemap

#endif  // FUSEMAP_MAPPING_SCAN_MATCHING_SCAN_INFORMATION_2D_H_
