#include "fusemap/mapping/scan_matching/scan_information_2d.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "fusemap/mapping/probability_values.h"

namespace fusemap {
namespace mapping {
namespace {

constexpr int kNeighbours = 4;
constexpr double kMaxNeighbourDistanceM = 2.0;
// Spread along the line against across it, as a ratio of variances (a factor ~3.2 in metres).
constexpr double kMinLineVarianceRatio = 10.0;
// A slide turns with the wall only where turning takes away nearly all that the slide costs
// the scan's lines. Round a curved wall it takes nearly all (simulated ring corridors of radius
// 21 and 28 m: 0.988-1.000 of it, 6,337 matches); along a straight corridor a few points off its
// walls (a door frame) give a turn of up to 0.02 rad/m that is not there and that takes 2 % of
// the cost, 41 % at most (simulated corridor world, 1,510 matches), and a slide of metres along
// the corridor would turn it into a heading error of degrees. (A threshold on the turn itself,
// 0.05 rad/m, took rings of radius above 20 m for straight: a 21 m ring's loop closures came
// out 3-6 degrees off.)
constexpr double kMinTurnShareOfSlideCost = 0.9;

}  // namespace

double ScanInformation2D::TranslationRatio() const {
  if (!(strongest_translation > 0.0)) return 0.0;
  return weakest_translation / strongest_translation;
}

namespace {

// Lines are fitted among all of `cloud`'s points; only those with counts[i] contribute (all
// when counts is null). Fitting among the counted points alone would invent structure: a point
// whose wall neighbours were not counted takes neighbours across the corridor as its line.
ScanInformation2D ComputeInformation(const sensor::PointCloud2d& cloud,
                                     const std::vector<bool>* counts) {
  ScanInformation2D result;
  const size_t n = cloud.size();
  if (n < 3) return result;
  std::vector<std::pair<double, size_t>> by_distance;
  by_distance.reserve(n);
  for (size_t i = 0; i < n; ++i) {
    if (counts != nullptr && !(*counts)[i]) continue;
    const Eigen::Vector2d p = cloud[i].cast<double>();
    // Brute force: loop-closure clouds hold a few hundred points, and only matches that passed
    // the score are asked about.
    by_distance.clear();
    for (size_t j = 0; j < n; ++j) {
      if (j == i) continue;
      const double d2 = (cloud[j].cast<double>() - p).squaredNorm();
      if (d2 <= kMaxNeighbourDistanceM * kMaxNeighbourDistanceM) by_distance.emplace_back(d2, j);
    }
    if (by_distance.size() < 2) continue;
    const size_t k = std::min<size_t>(kNeighbours, by_distance.size());
    std::partial_sort(by_distance.begin(), by_distance.begin() + k, by_distance.end());
    Eigen::Vector2d mean = p;
    for (size_t m = 0; m < k; ++m) mean += cloud[by_distance[m].second].cast<double>();
    mean /= static_cast<double>(k + 1);
    Eigen::Matrix2d covariance = (p - mean) * (p - mean).transpose();
    for (size_t m = 0; m < k; ++m) {
      const Eigen::Vector2d d = cloud[by_distance[m].second].cast<double>() - mean;
      covariance += d * d.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> line(covariance);
    if (!(line.eigenvalues()(1) > kMinLineVarianceRatio * line.eigenvalues()(0))) continue;
    const Eigen::Vector2d normal = line.eigenvectors().col(0);
    // Point-to-line residual normal . (R p + t): its gradient over [x, y, angle] at the pose.
    Eigen::Vector3d J;
    J << normal, normal.dot(Eigen::Vector2d(-p.y(), p.x()));
    result.information += J * J.transpose();
    ++result.points_on_lines;
  }
  result.information /= static_cast<double>(n);
  if (result.points_on_lines == 0 || !result.information.allFinite()) {
    result.information.setZero();
    return result;
  }
  const Eigen::Matrix2d H_tt = result.information.topLeftCorner<2, 2>();
  const Eigen::Vector2d H_ta = result.information.topRightCorner<2, 1>();
  const double H_aa = result.information(2, 2);
  // An angle the points do not hold (every line through the origin) leaves translation as is.
  const Eigen::Matrix2d marginal =
      H_aa > 1e-12 ? Eigen::Matrix2d(H_tt - H_ta * H_ta.transpose() / H_aa) : H_tt;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(marginal);
  // Ascending eigenvalues; rounding can leave the smallest a hair below zero.
  result.weakest_translation = std::max(0.0, eigen.eigenvalues()(0));
  result.strongest_translation = std::max(0.0, eigen.eigenvalues()(1));
  result.weakest_direction = eigen.eigenvectors().col(0).normalized();
  // The angle that minimises the cost for that translation (the one the Schur complement
  // assumed), -coupling / H_aa; it takes coupling^2 / H_aa off the slide's cost without turning.
  const Eigen::Vector2d& along = result.weakest_direction;
  const double slide_cost = along.dot(H_tt * along);
  const double coupling = H_ta.dot(along);
  if (H_aa > 1e-12 && slide_cost > 0.0 &&
      coupling * coupling >= kMinTurnShareOfSlideCost * H_aa * slide_cost) {
    result.weakest_turn_rad_per_m = -coupling / H_aa;
  }
  return result;
}

}  // namespace

ScanInformation2D ComputeScanInformation2D(const sensor::PointCloud2d& cloud) {
  return ComputeInformation(cloud, nullptr);
}

ScanInformation2D ComputeMatchedScanInformation2D(const ProbabilityGrid& grid,
                                                  const common::Rigid2d& T_grid_scan,
                                                  const sensor::PointCloud2d& cloud,
                                                  float min_probability) {
  const Eigen::Matrix2f rotation =
      Eigen::Rotation2Df(static_cast<float>(T_grid_scan.angle_rad())).matrix();
  const Eigen::Vector2f translation = T_grid_scan.translation().cast<float>();
  std::vector<bool> confirmed(cloud.size());
  for (size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Array2i cell = grid.limits().GetCellIndex(rotation * cloud[i] + translation);
    confirmed[i] = grid.GetProbabilityOr(cell, kMinProbability) >= min_probability;
  }
  return ComputeInformation(cloud, &confirmed);
}

Eigen::Vector2d UnpinnedDirection2D(const sensor::PointCloud2d& cloud, double min_ratio) {
  const ScanInformation2D information = ComputeScanInformation2D(cloud);
  if (information.TranslationRatio() >= min_ratio) return Eigen::Vector2d::Zero();
  return information.weakest_direction;
}

}  // namespace mapping
}  // namespace fusemap
