#ifndef FUSEMAP_MAPPING_SCAN_MATCHING_MATCH_EVIDENCE_2D_H_
#define FUSEMAP_MAPPING_SCAN_MATCHING_MATCH_EVIDENCE_2D_H_

#include "fusemap/common/rigid_transform.h"
#include "fusemap/mapping/probability_grid.h"
#include "fusemap/sensor/sensor_types.h"

namespace fusemap {
namespace mapping {

// How much better `candidate` explains `cloud` than `reference` does (both T_grid_tracking), as
// a paired test over the points: the mean over points of the grid probability at the point's
// cell under `candidate` minus under `reference` (`unknown_probability` where the grid has
// seen nothing or ends), divided by that mean's standard error. A match that beats another
// pose by chance (a corridor it slides along, a second room that looks the same) gains little
// against the spread of its points' gains. +inf if every point gains the same positive amount;
// 0 if the mean gain is not positive or the cloud is empty.
double GainInStandardErrors(const ProbabilityGrid& grid, float unknown_probability,
                            const common::Rigid2d& reference, const common::Rigid2d& candidate,
                            const sensor::PointCloud2d& cloud);

}  // namespace mapping
}  // namespace fusemap

#endif  // FUSEMAP_MAPPING_SCAN_MATCHING_MATCH_EVIDENCE_2D_H_
