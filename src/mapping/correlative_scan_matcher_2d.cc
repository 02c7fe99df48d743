#include "fusemap/mapping/scan_matching/correlative_scan_matcher_2d.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cassert>
#include <cmath>

namespace fusemap {
namespace mapping {

double ComputeAngularStep(double max_range_m, double resolution_m) {
  assert(resolution_m > 0.0);
  // A slightly smaller step than eq. 7 so the farthest point never jumps a whole cell.
  constexpr double kSafetyMargin = 1.0 - 1e-3;
  // Below a few cells of range eq. 7 degenerates; a cell-sized range gives the coarsest step.
  const double range_m = std::max(max_range_m, resolution_m);
  const double cos_step = 1.0 - resolution_m * resolution_m / (2.0 * range_m * range_m);
  return kSafetyMargin * std::acos(std::max(-1.0, cos_step));
}

SearchParameters::SearchParameters(double linear_search_window_m,
                                   double angular_search_window_rad,
                                   const sensor::PointCloud2d& cloud, double resolution_m)
    : resolution_m(resolution_m) {
  assert(linear_search_window_m >= 0.0 && angular_search_window_rad >= 0.0);
  float max_range_m = 0.f;
  for (const Eigen::Vector2f& point : cloud) max_range_m = std::max(max_range_m, point.norm());
  angular_step_rad = ComputeAngularStep(max_range_m, resolution_m);
  num_angular_perturbations = static_cast<int>(std::ceil(angular_search_window_rad / angular_step_rad));
  num_scans = 2 * num_angular_perturbations + 1;
  const int num_linear = static_cast<int>(std::ceil(linear_search_window_m / resolution_m));
  linear_bounds.assign(num_scans, LinearBounds{-num_linear, num_linear, -num_linear, num_linear});
}

SearchParameters::SearchParameters(int num_linear_perturbations, int num_angular_perturbations,
                                   double angular_step_rad, double resolution_m)
    : num_angular_perturbations(num_angular_perturbations),
      angular_step_rad(angular_step_rad),
      resolution_m(resolution_m),
      num_scans(2 * num_angular_perturbations + 1) {
  linear_bounds.assign(num_scans,
                       LinearBounds{-num_linear_perturbations, num_linear_perturbations,
                                    -num_linear_perturbations, num_linear_perturbations});
}

void SearchParameters::ShrinkToFit(const std::vector<DiscreteScan2D>& scans,
                                   const MapLimits& limits) {
  assert(static_cast<int>(scans.size()) == num_scans);
  for (int i = 0; i < num_scans; ++i) {
    if (scans[i].empty()) continue;
    Eigen::Array2i min_cell = scans[i].front();
    Eigen::Array2i max_cell = scans[i].front();
    for (const Eigen::Array2i& cell : scans[i]) {
      min_cell = min_cell.min(cell);
      max_cell = max_cell.max(cell);
    }
    LinearBounds& bounds = linear_bounds[i];
    bounds.min_x = std::max(bounds.min_x, -max_cell.x());
    bounds.max_x = std::min(bounds.max_x, limits.num_x_cells - 1 - min_cell.x());
    bounds.min_y = std::max(bounds.min_y, -max_cell.y());
    bounds.max_y = std::min(bounds.max_y, limits.num_y_cells - 1 - min_cell.y());
  }
}

std::vector<sensor::PointCloud2d> GenerateRotatedScans(const sensor::PointCloud2d& cloud,
                                                       const SearchParameters& params) {
  std::vector<sensor::PointCloud2d> rotated_scans;
  rotated_scans.reserve(params.num_scans);
  for (int i = 0; i < params.num_scans; ++i) {
    const double angle_rad = (i - params.num_angular_perturbations) * params.angular_step_rad;
    const Eigen::Matrix2f rotation = Eigen::Rotation2Df(static_cast<float>(angle_rad)).matrix();
    sensor::PointCloud2d rotated;
    rotated.reserve(cloud.size());
    for (const Eigen::Vector2f& point : cloud) rotated.push_back(rotation * point);
    rotated_scans.push_back(std::move(rotated));
  }
  return rotated_scans;
}

std::vector<DiscreteScan2D> DiscretizeScans(const MapLimits& limits,
                                            const std::vector<sensor::PointCloud2d>& scans,
                                            const Eigen::Vector2f& initial_translation) {
  std::vector<DiscreteScan2D> discrete_scans;
  discrete_scans.reserve(scans.size());
  for (const sensor::PointCloud2d& scan : scans) {
    // Sized first and written by index: with push_back, each cell went through the stack and
    // the loop waited on it (local SLAM's wide search discretises hundreds of rotated scans).
    DiscreteScan2D discrete(scan.size());
    for (size_t i = 0; i < scan.size(); ++i) {
      discrete[i] = limits.GetCellIndex(scan[i] + initial_translation);
    }
    discrete_scans.push_back(std::move(discrete));
  }
  return discrete_scans;
}

}  // namespace mapping
}  // namespace fusemap
