#include "fusemap/cloud_eval/landmark_eval.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "fusemap/common/math.h"

namespace fusemap {
namespace cloud_eval {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kMinPoints = 30;
constexpr int kNumPairs = 6;
constexpr double kPillarMarginM = 0.15;
constexpr double kPillarZMinM = 0.3, kPillarZMaxM = 2.0;
constexpr double kTopFootprintMarginM = 0.05;
constexpr double kTopHeightToleranceM = 0.04;
constexpr double kTopBelowCameraM = 0.05;

// Kasa (1976): minimises sum (x² + y² + D x + E y + F)², linear in D, E, F. Coordinates are
// taken relative to the true axis for conditioning.
LandmarkEstimate FitPillar(const sim::Prism& pillar, const cloud::ColorCloud& cloud) {
  std::vector<Eigen::Vector2d> xy;
  for (const cloud::ColorPoint& p : cloud) {
    const Eigen::Vector2d d = Eigen::Vector2d(p.x, p.y) - pillar.centre_m;
    if (p.z > kPillarZMinM && p.z < kPillarZMaxM && d.norm() < pillar.radius_m + kPillarMarginM) {
      xy.push_back(d);
    }
  }
  LandmarkEstimate estimate;
  estimate.points = static_cast<int>(xy.size());
  if (estimate.points < kMinPoints) return estimate;
  Eigen::MatrixXd A(xy.size(), 3);
  Eigen::VectorXd b(xy.size());
  for (size_t i = 0; i < xy.size(); ++i) {
    A.row(i) << xy[i].x(), xy[i].y(), 1.0;
    b(i) = -xy[i].squaredNorm();
  }
  const Eigen::Vector3d def = A.colPivHouseholderQr().solve(b);
  estimate.found = def.allFinite();
  estimate.xy_m = pillar.centre_m + Eigen::Vector2d(-0.5 * def(0), -0.5 * def(1));
  return estimate;
}

LandmarkEstimate FitBoxTop(const sim::Prism& box, const cloud::ColorCloud& cloud) {
  const Eigen::Rotation2Dd R_world_box(box.yaw_rad);
  std::vector<double> u, v;
  for (const cloud::ColorPoint& p : cloud) {
    if (std::abs(p.z - box.z_max_m) > kTopHeightToleranceM) continue;
    const Eigen::Vector2d q = R_world_box.inverse() * (Eigen::Vector2d(p.x, p.y) - box.centre_m);
    if (std::abs(q.x()) <= box.half_size_m.x() + kTopFootprintMarginM &&
        std::abs(q.y()) <= box.half_size_m.y() + kTopFootprintMarginM) {
      u.push_back(q.x());
      v.push_back(q.y());
    }
  }
  LandmarkEstimate estimate;
  estimate.points = static_cast<int>(u.size());
  if (estimate.points < kMinPoints) return estimate;
  const Eigen::Vector2d centre_box(
      0.5 * (common::Percentile(u, 0.02) + common::Percentile(u, 0.98)),
      0.5 * (common::Percentile(v, 0.02) + common::Percentile(v, 0.98)));
  estimate.found = true;
  estimate.xy_m = box.centre_m + R_world_box * centre_box;
  return estimate;
}

}  // namespace

std::vector<Landmark> MeasurableLandmarks(const sim::World& world, double camera_height_m) {
  std::vector<Landmark> pillars, boxes;
  int box_index = 0;
  for (const sim::Prism& prism : world.prisms) {
    if (prism.shape == sim::Prism::Shape::kCircle) {
      pillars.push_back({Landmark::Kind::kPillar, "pillar" + std::to_string(pillars.size()), prism});
    } else if (prism.z_max_m < world.ceiling_height_m - 1e-6) {
      if (prism.z_max_m <= camera_height_m - kTopBelowCameraM) {
        boxes.push_back({Landmark::Kind::kBoxTop, "box" + std::to_string(box_index), prism});
      }
      ++box_index;
    }
  }
  pillars.insert(pillars.end(), boxes.begin(), boxes.end());
  return pillars;
}

LandmarkEstimate EstimateLandmark(const Landmark& landmark, const cloud::ColorCloud& cloud_world) {
  return landmark.kind == Landmark::Kind::kPillar ? FitPillar(landmark.prism, cloud_world)
                                                  : FitBoxTop(landmark.prism, cloud_world);
}

std::vector<LandmarkPairResult> EvaluateLandmarkPairs(const sim::World& world,
                                                      const cloud::ColorCloud& cloud_world,
                                                      double camera_height_m) {
  const std::vector<Landmark> landmarks = MeasurableLandmarks(world, camera_height_m);
  std::vector<LandmarkEstimate> estimates;
  for (const Landmark& l : landmarks) estimates.push_back(EstimateLandmark(l, cloud_world));
  std::vector<LandmarkPairResult> pairs;
  for (size_t i = 0; i + 1 < landmarks.size() && static_cast<int>(pairs.size()) < kNumPairs; ++i) {
    LandmarkPairResult pair;
    pair.a = landmarks[i].name;
    pair.b = landmarks[i + 1].name;
    pair.true_m = (landmarks[i].prism.centre_m - landmarks[i + 1].prism.centre_m).norm();
    if (estimates[i].found && estimates[i + 1].found) {
      pair.measured_m = (estimates[i].xy_m - estimates[i + 1].xy_m).norm();
      pair.rel_err = std::abs(pair.measured_m - pair.true_m) / pair.true_m;
    } else {
      pair.measured_m = kNaN;
      pair.rel_err = kNaN;
    }
    pairs.push_back(pair);
  }
  return pairs;
}

std::string FormatLandmarkSummary(const std::vector<LandmarkPairResult>& pairs) {
  double max_err = kNaN;
  int found = 0;
  for (const LandmarkPairResult& p : pairs) {
    if (std::isnan(p.rel_err)) continue;
    ++found;
    max_err = std::isnan(max_err) ? p.rel_err : std::max(max_err, p.rel_err);
  }
  char line[128];
  std::snprintf(line, sizeof(line), "landmark_pair_max_rel_err=%.5f landmark_pairs_found=%d/%zu",
                max_err, found, pairs.size());
  return line;
}

std::string FormatLandmarkPair(const LandmarkPairResult& pair) {
  char line[192];
  std::snprintf(line, sizeof(line),
                "landmark_pair a=%s b=%s true_m=%.4f measured_m=%.4f rel_err=%.5f", pair.a.c_str(),
                pair.b.c_str(), pair.true_m, pair.measured_m, pair.rel_err);
  return line;
}

}  // namespace cloud_eval
}  // namespace fusemap
