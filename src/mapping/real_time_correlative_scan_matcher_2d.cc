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
    : options_(options) {
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

  const float unknown_probability = static_cast<float>(options_.unknown_probability);
  bool have_best = false;
  Candidate2D best(params.num_angular_perturbations, 0, 0, params);
  for (int i = 0; i < params.num_scans; ++i) {
    const SearchParameters::LinearBounds& bounds = params.linear_bounds[i];
    for (int dx = bounds.min_x; dx <= bounds.max_x; ++dx) {
      for (int dy = bounds.min_y; dy <= bounds.max_y; ++dy) {
        Candidate2D candidate(i, dx, dy, params);
        const Eigen::Array2i offset(dx, dy);
        double sum = 0.0;
        for (const Eigen::Array2i& cell : scans[i]) {
          sum += grid.GetProbabilityOr(cell + offset, unknown_probability);
        }
        // Cartographer's prior on the distance from the prediction.
        const double penalty =
            std::hypot(candidate.x_m, candidate.y_m) * options_.translation_delta_cost_weight +
            std::abs(candidate.angle_rad) * options_.rotation_delta_cost_weight;
        candidate.score = sum / static_cast<double>(scans[i].size()) * std::exp(-penalty * penalty);
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
