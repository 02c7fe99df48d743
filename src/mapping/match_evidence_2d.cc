#include "fusemap/mapping/scan_matching/match_evidence_2d.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace fusemap {
namespace mapping {

double GainInStandardErrors(const ProbabilityGrid& grid, float unknown_probability,
                            const common::Rigid2d& reference, const common::Rigid2d& candidate,
                            const sensor::PointCloud2d& cloud) {
  if (cloud.empty()) return 0.0;
  const auto probability_at = [&grid, unknown_probability](const Eigen::Matrix2f& rotation,
                                                           const Eigen::Vector2f& translation,
                                                           const Eigen::Vector2f& point) {
    return static_cast<double>(grid.GetProbabilityOr(
        grid.limits().GetCellIndex(rotation * point + translation), unknown_probability));
  };
  const Eigen::Matrix2f reference_rotation =
      Eigen::Rotation2Df(static_cast<float>(reference.angle_rad())).matrix();
  const Eigen::Matrix2f candidate_rotation =
      Eigen::Rotation2Df(static_cast<float>(candidate.angle_rad())).matrix();
  const Eigen::Vector2f reference_translation = reference.translation().cast<float>();
  const Eigen::Vector2f candidate_translation = candidate.translation().cast<float>();
  double sum = 0.0;
  double sum_squares = 0.0;
  for (const Eigen::Vector2f& point : cloud) {
    const double gain = probability_at(candidate_rotation, candidate_translation, point) -
                        probability_at(reference_rotation, reference_translation, point);
    sum += gain;
    sum_squares += gain * gain;
  }
  const double n = static_cast<double>(cloud.size());
  const double mean = sum / n;
  if (!(mean > 0.0)) return 0.0;
  // The per-point gains' sample variance; the mean's standard error is sqrt(variance / n).
  const double variance =
      n > 1.0 ? std::max(0.0, (sum_squares - n * mean * mean) / (n - 1.0)) : 0.0;
  if (variance == 0.0) return std::numeric_limits<double>::infinity();
  return mean / std::sqrt(variance / n);
}

}  // namespace mapping
}  // namespace fusemap
