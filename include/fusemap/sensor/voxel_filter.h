#ifndef FUSEMAP_SENSOR_VOXEL_FILTER_H_
#define FUSEMAP_SENSOR_VOXEL_FILTER_H_

#include <string>

#include "fusemap/common/config_reader.h"
#include "fusemap/sensor/sensor_types.h"

namespace fusemap {
namespace sensor {

// Keeps the first point falling into each square voxel [k * edge, (k + 1) * edge), in input
// order, so dense near-field returns do not dominate matching or insertion (Cartographer keeps
// one sample point per voxel rather than a centroid, which would invent points on no surface).
PointCloud2d VoxelFilter(const PointCloud2d& points, float edge_length_m);
// Filters returns and misses separately; the origin is unchanged.
RangeData VoxelFilter(const RangeData& range_data, float edge_length_m);

// Cartographer's adaptive voxel filter: the coarsest voxel edge (at most max_length_m) that
// still leaves at least min_num_points, found by halving then bisecting to within 10 %.
// Points farther than max_range_m from the frame origin are dropped first.
struct AdaptiveVoxelFilterOptions {
  float max_length_m = 0.5f;
  int min_num_points = 200;
  float max_range_m = 50.f;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

AdaptiveVoxelFilterOptions ParseAdaptiveVoxelFilterOptions(common::ConfigReader& reader);

// Returns at least min_num_points points whenever the range-limited input has that many.
PointCloud2d AdaptiveVoxelFilter(const PointCloud2d& points,
                                 const AdaptiveVoxelFilterOptions& options);

}  // namespace sensor
}  // namespace fusemap

#endif  // FUSEMAP_SENSOR_VOXEL_FILTER_H_
