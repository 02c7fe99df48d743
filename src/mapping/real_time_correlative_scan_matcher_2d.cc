#include "fusemap/mapping/scan_matching/real_time_correlative_scan_matcher_2d.h"

#include <Eigen/Geometry>
#include <cassert>
#include <cmath>
#include <vector>

#include "fusemap/mapping/scan_matching/correlative_scan_matcher_2d.h"

namespace fusemap {
namespace mapping {

void RealTimeCorrelativeScanMatcherOptions2D::Check(common::OptionChecker* check) const {
  check->Require(linear_search_window_m >= 0.0, "linear_search_window_m", "must be >= 0");
  check->Require(angular_search_window_rad >= 0.0 && angular_search_window_rad <= common::kPi,
                 "angular_search_window_rad", "must be in [0, pi]");
  check->Require(translation_delta_cost_weight >= 0.0, "translation_delta_cost_weight",
                 "must be >= 0");
  check->Require(rotation_delta_cost_weight >= 0.0, "rotation_delta_cost_weight", "must be >= 0");
  // Compared as the float the grid uses: the YAML value 0.1 is a double just below 0.1f.
  const float unknown = static_cast<float>(unknown_probability);
  check->Require(unknown >= kMinProbability && unknown <= kMaxProbability, "unknown_probability",
                 "must be in [0.1, 0.9]");
}

bool RealTimeCorrelativeScanMatcherOptions2D::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

RealTimeCorrelativeScanMatcherOptions2D ParseRealTimeCorrelativeScanMatcherOptions2D(
    common::ConfigReader& reader) {
  RealTimeCorrelativeScanMatcherOptions2D options;
  reader.Get("linear_search_window_m", &options.linear_search_window_m);
  reader.Get("angular_search_window_rad", &options.angular_search_window_rad);
  reader.Get("translation_delta_cost_weight", &options.translation_delta_cost_weight);
  reader.Get("rotation_delta_cost_weight", &options.rotation_delta_cost_weight);
  reader.Get("unknown_probability", &options.unknown_probability);
  reader.CheckOptions(options);
  return options;
}

RealTimeCorrelativeScanMatcher2D::RealTimeCorrelativeScanMatcher2D(
    const RealTimeCorrelativeScanMatcherOptions2D& options)
    : options_(options),
      probability_of_value_(
          ComputeValueToProbabilityTable(static_cast<float>(options.unknown_probability))) {
  std::string error;
  assert(options_.IsValid(&error));
  (void)error;
}

double RealTimeCorrelativeScanMatcher2D::Match(const common::Rigid2d& initial_pose,
                                               const sensor::PointCloud2d& cloud,
                                               const ProbabilityGrid& grid,
                                               common::Rigid2d* pose,
                                               bool* at_window_edge) const {
  assert(pose != nullptr);
  *pose = initial_pose;
  if (at_window_edge != nullptr) *at_window_edge = false;
  if (cloud.empty()) return 0.0;

  const Eigen::Matrix2f initial_rotation =
      Eigen::Rotation2Df(static_cast<float>(initial_pose.angle_rad())).matrix();
  sensor::PointCloud2d rotated_cloud;
  rotated_cloud.reserve(cloud.size());
  for (const Eigen::Vector2f& point : cloud) rotated_cloud.push_back(initial_rotation * point);

  const SearchParameters params(options_.linear_search_window_m,
                                options_.angular_search_window_rad, rotated_cloud,
                                grid.limits().resolution_m);
  const std::vector<DiscreteScan2D> scans =
      DiscretizeScans(grid.limits(), GenerateRotatedScans(rotated_cloud, params),
                      initial_pose.translation().cast<float>());

  // Each candidate's sum is grid.GetProbabilityOr(cell + offset, unknown_probability) over the
  // scan's cells in order, read through the table with all offsets of one cell together (they
  // lie in a few neighbouring rows): this loop is most of local SLAM's time.
  const float unknown_probability = static_cast<float>(options_.unknown_probability);
  const MapLimits& limits = grid.limits();
  const uint16_t* const cells = grid.cells().data();
  const float* const probability_of_value = probability_of_value_.data();
  constexpr uint16_t kValueMask = static_cast<uint16_t>(~kUpdateMarker);
  std::vector<double> sums;
  bool have_best = false;
  Candidate2D best(params.num_angular_perturbations, 0, 0, params);
  for (int i = 0; i < params.num_scans; ++i) {
    const SearchParameters::LinearBounds& bounds = params.linear_bounds[i];
    const int size_x = bounds.max_x - bounds.min_x + 1;
    const int size_y = bounds.max_y - bounds.min_y + 1;
    // Candidate (dx, dy) sums at (dx - min_x) * size_y + dy - min_y: the order they are scored in.
    sums.assign(static_cast<size_t>(size_x) * size_y, 0.0);
    for (const Eigen::Array2i& scan_cell : scans[i]) {
      const Eigen::Array2i low = scan_cell + Eigen::Array2i(bounds.min_x, bounds.min_y);
      const Eigen::Array2i high = scan_cell + Eigen::Array2i(bounds.max_x, bounds.max_y);
      double* sum = sums.data();
      if (limits.Contains(low) && limits.Contains(high)) {
        const uint16_t* const first = cells + limits.FlatIndex(low);
        for (int x = 0; x < size_x; ++x) {
          for (int y = 0; y < size_y; ++y) {
            *sum++ += probability_of_value[first[y * limits.num_x_cells + x] & kValueMask];
          }
        }
        continue;
      }
      for (int x = 0; x < size_x; ++x) {
        for (int y = 0; y < size_y; ++y) {
          const Eigen::Array2i cell = low + Eigen::Array2i(x, y);
          *sum++ += limits.Contains(cell)
                        ? probability_of_value[cells[limits.FlatIndex(cell)] & kValueMask]
                        : unknown_probability;
        }
      }
    }
    const double* sum = sums.data();
    for (int dx = bounds.min_x; dx <= bounds.max_x; ++dx) {
      for (int dy = bounds.min_y; dy <= bounds.max_y; ++dy) {
        Candidate2D candidate(i, dx, dy, params);
        // Cartographer's prior on the distance from the prediction.
        const double penalty =
            std::hypot(candidate.x_m, candidate.y_m) * options_.translation_delta_cost_weight +
            std::abs(candidate.angle_rad) * options_.rotation_delta_cost_weight;
        candidate.score =
            *sum++ / static_cast<double>(scans[i].size()) * std::exp(-penalty * penalty);
        if (!have_best || candidate > best) {
          best = candidate;
          have_best = true;
        }
      }
    }
  }
  if (at_window_edge != nullptr) {
    const SearchParameters::LinearBounds& bounds = params.linear_bounds[best.scan_index];
    *at_window_edge = (params.num_scans > 1 &&
                       (best.scan_index == 0 || best.scan_index == params.num_scans - 1)) ||
                      best.x_offset_cells == bounds.min_x || best.x_offset_cells == bounds.max_x ||
                      best.y_offset_cells == bounds.min_y || best.y_offset_cells == bounds.max_y;
  }
  *pose = common::Rigid2d(initial_pose.translation() + Eigen::Vector2d(best.x_m, best.y_m),
                          initial_pose.angle_rad() + best.angle_rad);
  return best.score;
}

}  // namespace mapping
}  // namespace fusemap
