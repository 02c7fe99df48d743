#include "fusemap/pose_graph/odometry_calibration.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <Eigen/Dense>

#include "fusemap/common/math.h"

namespace fusemap {
namespace pose_graph {

namespace {

// Linear interpolation in time between the bracketing samples (clamped at the ends), the same
// rule DensifyWithOdometry uses to attach a node to the odometry.
struct Bracket {
  size_t lower = 0;
  size_t upper = 0;
  double fraction = 0.0;
};

Bracket BracketAt(const std::vector<sensor::OdometryData>& odometry, double stamp_s) {
  const auto it = std::lower_bound(
      odometry.begin(), odometry.end(), stamp_s,
      [](const sensor::OdometryData& o, double t) { return o.stamp_s < t; });
  if (it == odometry.begin()) return {0, 0, 0.0};
  if (it == odometry.end()) return {odometry.size() - 1, odometry.size() - 1, 0.0};
  const size_t upper = static_cast<size_t>(it - odometry.begin());
  const double span = odometry[upper].stamp_s - odometry[upper - 1].stamp_s;
  return {upper - 1, upper, span > 0 ? (stamp_s - odometry[upper - 1].stamp_s) / span : 1.0};
}

double ScalarAt(const std::vector<double>& values, const Bracket& b) {
  return values[b.lower] + b.fraction * (values[b.upper] - values[b.lower]);
}

common::Rigid2d PoseAt(const std::vector<sensor::OdometryData>& odometry, const Bracket& b) {
  return common::Interpolate(odometry[b.lower].pose, odometry[b.upper].pose, b.fraction);
}

// Distance along the sample's own x axis counts forward; backing up bends the path the other way.
double SignedDistance(const common::Rigid2d& delta) {
  const double d = delta.translation().norm();
  return delta.x() < 0.0 ? -d : d;
}

// Huber weights for IRLS from the residuals' robust scale.
std::vector<double> HuberWeights(const std::vector<double>& abs_residuals, double threshold_sigma) {
  const double sigma = std::max(1.4826 * common::Percentile(abs_residuals, 0.5), 1e-9);
  const double threshold = threshold_sigma * sigma;
  std::vector<double> weights;
  weights.reserve(abs_residuals.size());
  for (double r : abs_residuals) weights.push_back(r <= threshold ? 1.0 : threshold / r);
  return weights;
}

struct Interval {
  size_t node = 0;  // from nodes[node] to nodes[node + 1]
  Bracket from, to;
};

struct HeadingRow {
  double odometry_rotation_rad;  // sum of the raw increments' rotations
  double signed_distance_m;
  double slam_rotation_rad;  // unwrapped next to odometry_rotation_rad
};

}  // namespace

bool OdometryCalibration::IsIdentity() const {
  return translation_scale == 1.0 && rotation_scale == 1.0 && heading_drift_rad_per_m == 0.0;
}

void OdometryCalibrationOptions::Check(common::OptionChecker* check) const {
  check->Require(min_intervals >= 3, "min_intervals", "must be at least 3 (three parameters)");
  check->Require(min_distance_m >= 0.0, "min_distance_m", "must not be negative");
  check->Require(min_rotation_rad >= 0.0, "min_rotation_rad", "must not be negative");
  check->Require(max_scale_deviation > 0.0 && max_scale_deviation < 1.0, "max_scale_deviation",
                 "must be in (0, 1)");
  check->Require(max_heading_drift_rad_per_m > 0.0, "max_heading_drift_rad_per_m",
                 "must be positive");
  check->Require(robust_iterations >= 1, "robust_iterations", "must be at least 1");
  check->Require(huber_threshold_sigma > 0.0, "huber_threshold_sigma", "must be positive");
}

bool OdometryCalibrationOptions::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

common::Rigid2d CalibrateIncrement(const OdometryCalibration& calibration,
                                   const common::Rigid2d& delta) {
  const double angle_rad = calibration.rotation_scale * delta.angle_rad() +
                           calibration.heading_drift_rad_per_m * SignedDistance(delta);
  const double extra_rad = angle_rad - delta.angle_rad();
  return common::Rigid2d(
      calibration.translation_scale * (Eigen::Rotation2Dd(0.5 * extra_rad) * delta.translation()),
      angle_rad);
}

std::vector<sensor::OdometryData> ApplyOdometryCalibration(
    const OdometryCalibration& calibration, const std::vector<sensor::OdometryData>& odometry) {
  if (calibration.IsIdentity() || odometry.empty()) return odometry;
  std::vector<sensor::OdometryData> corrected;
  corrected.reserve(odometry.size());
  corrected.push_back(odometry.front());
  for (size_t i = 1; i < odometry.size(); ++i) {
    const common::Rigid2d delta = odometry[i - 1].pose.inverse() * odometry[i].pose;
    corrected.push_back(
        {odometry[i].stamp_s, corrected.back().pose * CalibrateIncrement(calibration, delta)});
  }
  return corrected;
}

bool FitOdometryCalibration(const std::vector<MapBuilder2D::TimedPose2d>& nodes,
                            const std::vector<sensor::OdometryData>& odometry,
                            const OdometryCalibrationOptions& options,
                            OdometryCalibration* calibration, std::string* reason) {
  assert(calibration != nullptr && reason != nullptr);
  *calibration = OdometryCalibration();
  if (odometry.size() < 2) {
    *reason = "fewer than two odometry samples";
    return false;
  }
  // Cumulative rotation and signed distance per sample: the heading model is linear in them.
  std::vector<double> rotation_rad(odometry.size(), 0.0), distance_m(odometry.size(), 0.0);
  for (size_t i = 1; i < odometry.size(); ++i) {
    const common::Rigid2d delta = odometry[i - 1].pose.inverse() * odometry[i].pose;
    rotation_rad[i] = rotation_rad[i - 1] + delta.angle_rad();
    distance_m[i] = distance_m[i - 1] + SignedDistance(delta);
  }
  // Only intervals inside the odometry's time span: outside it there is no odometry motion.
  std::vector<Interval> intervals;
  std::vector<HeadingRow> rows;
  double total_distance_m = 0.0, total_rotation_rad = 0.0;
  for (size_t i = 0; i + 1 < nodes.size(); ++i) {
    const auto& a = nodes[i];
    const auto& b = nodes[i + 1];
    if (!(b.stamp_s > a.stamp_s) || a.stamp_s < odometry.front().stamp_s ||
        b.stamp_s > odometry.back().stamp_s) {
      continue;
    }
    const Bracket ba = BracketAt(odometry, a.stamp_s);
    const Bracket bb = BracketAt(odometry, b.stamp_s);
    HeadingRow row;
    row.odometry_rotation_rad = ScalarAt(rotation_rad, bb) - ScalarAt(rotation_rad, ba);
    row.signed_distance_m = ScalarAt(distance_m, bb) - ScalarAt(distance_m, ba);
    row.slam_rotation_rad =
        row.odometry_rotation_rad +
        common::NormalizeAngle(b.pose.angle_rad() - a.pose.angle_rad() - row.odometry_rotation_rad);
    total_distance_m += std::abs(row.signed_distance_m);
    total_rotation_rad += std::abs(row.odometry_rotation_rad);
    rows.push_back(row);
    intervals.push_back({i, ba, bb});
  }
  if (static_cast<int>(rows.size()) < options.min_intervals ||
      total_distance_m < options.min_distance_m || total_rotation_rad < options.min_rotation_rad) {
    *reason = "too little motion between nodes to calibrate (" + std::to_string(rows.size()) +
              " intervals, " + std::to_string(total_distance_m) + " m, " +
              std::to_string(total_rotation_rad) + " rad)";
    return false;
  }

  // Heading: slam_rotation = rotation_scale * odometry_rotation + drift * signed_distance.
  std::vector<double> weights(rows.size(), 1.0), residuals(rows.size());
  Eigen::Vector2d heading(1.0, 0.0);
  for (int iteration = 0; iteration < options.robust_iterations; ++iteration) {
    Eigen::Matrix2d normal = Eigen::Matrix2d::Zero();
    Eigen::Vector2d rhs = Eigen::Vector2d::Zero();
    for (size_t i = 0; i < rows.size(); ++i) {
      const Eigen::Vector2d j(rows[i].odometry_rotation_rad, rows[i].signed_distance_m);
      normal += weights[i] * j * j.transpose();
      rhs += weights[i] * j * rows[i].slam_rotation_rad;
    }
    heading = normal.ldlt().solve(rhs);
    for (size_t i = 0; i < rows.size(); ++i) {
      residuals[i] = std::abs(rows[i].slam_rotation_rad -
                              heading.dot(Eigen::Vector2d(rows[i].odometry_rotation_rad,
                                                          rows[i].signed_distance_m)));
    }
    weights = HuberWeights(residuals, options.huber_threshold_sigma);
  }
  OdometryCalibration fitted;
  fitted.rotation_scale = heading.x();
  fitted.heading_drift_rad_per_m = heading.y();

  // Translation scale on the heading-corrected odometry: SLAM's node-to-node translation
  // against the odometry's, both in the earlier node's frame.
  const auto corrected = ApplyOdometryCalibration(fitted, odometry);
  std::vector<Eigen::Vector2d> t_odometry, t_slam;
  for (const Interval& interval : intervals) {
    t_odometry.push_back(
        (PoseAt(corrected, interval.from).inverse() * PoseAt(corrected, interval.to)).translation());
    t_slam.push_back(
        (nodes[interval.node].pose.inverse() * nodes[interval.node + 1].pose).translation());
  }
  std::fill(weights.begin(), weights.end(), 1.0);
  double scale = 1.0;
  for (int iteration = 0; iteration < options.robust_iterations; ++iteration) {
    double numerator = 0.0, denominator = 0.0;
    for (size_t i = 0; i < t_odometry.size(); ++i) {
      numerator += weights[i] * t_odometry[i].dot(t_slam[i]);
      denominator += weights[i] * t_odometry[i].squaredNorm();
    }
    if (!(denominator > 0.0)) break;
    scale = numerator / denominator;
    for (size_t i = 0; i < t_odometry.size(); ++i) {
      residuals[i] = (t_slam[i] - scale * t_odometry[i]).norm();
    }
    weights = HuberWeights(residuals, options.huber_threshold_sigma);
  }
  fitted.translation_scale = scale;

  if (!(std::abs(fitted.translation_scale - 1.0) <= options.max_scale_deviation) ||
      !(std::abs(fitted.rotation_scale - 1.0) <= options.max_scale_deviation) ||
      !(std::abs(fitted.heading_drift_rad_per_m) <= options.max_heading_drift_rad_per_m)) {
    *reason = "fit out of bounds (translation_scale " + std::to_string(fitted.translation_scale) +
              ", rotation_scale " + std::to_string(fitted.rotation_scale) +
              ", heading_drift_rad_per_m " + std::to_string(fitted.heading_drift_rad_per_m) + ")";
    return false;
  }
  *calibration = fitted;
  return true;
}

}  // namespace pose_graph
}  // namespace fusemap
