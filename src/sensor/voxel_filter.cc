#include "fusemap/sensor/voxel_filter.h"

#include <cassert>
#include <cmath>
#include <cstdint>
#include <unordered_set>

namespace fusemap {
namespace sensor {
namespace {

uint64_t VoxelKey(const Eigen::Vector2f& point, float edge_length_m) {
  const int64_t x = static_cast<int64_t>(std::floor(point.x() / edge_length_m));
  const int64_t y = static_cast<int64_t>(std::floor(point.y() / edge_length_m));
  return (static_cast<uint64_t>(static_cast<uint32_t>(x)) << 32) |
         static_cast<uint64_t>(static_cast<uint32_t>(y));
}

}  // namespace

PointCloud2d VoxelFilter(const PointCloud2d& points, float edge_length_m) {
  assert(edge_length_m > 0.f);
  std::unordered_set<uint64_t> occupied;
  occupied.reserve(points.size());
  PointCloud2d result;
  for (const Eigen::Vector2f& point : points) {
    if (occupied.insert(VoxelKey(point, edge_length_m)).second) result.push_back(point);
  }
  return result;
}

RangeData VoxelFilter(const RangeData& range_data, float edge_length_m) {
  RangeData result;
  result.origin = range_data.origin;
  result.returns = VoxelFilter(range_data.returns, edge_length_m);
  result.misses = VoxelFilter(range_data.misses, edge_length_m);
  return result;
}

void AdaptiveVoxelFilterOptions::Check(common::OptionChecker* check) const {
  check->Require(max_length_m > 0.f, "max_length_m", "must be > 0");
  check->Require(min_num_points >= 1, "min_num_points", "must be >= 1");
  check->Require(max_range_m > 0.f, "max_range_m", "must be > 0");
}

bool AdaptiveVoxelFilterOptions::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

AdaptiveVoxelFilterOptions ParseAdaptiveVoxelFilterOptions(common::ConfigReader& reader) {
  AdaptiveVoxelFilterOptions options;
  reader.Get("max_length_m", &options.max_length_m);
  reader.Get("min_num_points", &options.min_num_points);
  reader.Get("max_range_m", &options.max_range_m);
  reader.CheckOptions(options);
  return options;
}

PointCloud2d AdaptiveVoxelFilter(const PointCloud2d& points,
                                 const AdaptiveVoxelFilterOptions& options) {
  PointCloud2d in_range;
  in_range.reserve(points.size());
  const float max_range_sq = options.max_range_m * options.max_range_m;
  for (const Eigen::Vector2f& point : points) {
    if (point.squaredNorm() <= max_range_sq) in_range.push_back(point);
  }
  const size_t min_num_points = static_cast<size_t>(options.min_num_points);
  if (in_range.size() <= min_num_points) return in_range;

  PointCloud2d result = VoxelFilter(in_range, options.max_length_m);
  if (result.size() >= min_num_points) return result;

  // Halve until dense enough, then bisect between the last too-coarse and the first dense
  // enough edge length. Point counts fall (almost) monotonically with edge length.
  for (float high_m = options.max_length_m; high_m > 1e-2f * options.max_length_m;
       high_m /= 2.f) {
    float low_m = high_m / 2.f;
    result = VoxelFilter(in_range, low_m);
    if (result.size() < min_num_points) continue;
    while ((high_m - low_m) / low_m > 0.1f) {
      const float mid_m = 0.5f * (low_m + high_m);
      PointCloud2d candidate = VoxelFilter(in_range, mid_m);
      if (candidate.size() >= min_num_points) {
        low_m = mid_m;
        result.swap(candidate);
      } else {
        high_m = mid_m;
      }
    }
    return result;
  }
  // Even 1 % of max_length_m is too coarse (points nearly coincide): keep them all.
  return in_range;
}

}  // namespace sensor
}  // namespace fusemap
