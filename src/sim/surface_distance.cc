#include "fusemap/sim/surface_distance.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace fusemap {
namespace sim {
namespace {

// Signed distance to an axis-aligned box or capped cylinder given the per-axis excess `d` of
// the point over the half extents (negative inside): the usual box SDF, exact both outside
// (norm of the positive part) and inside (largest, i.e. least negative, component).
template <int N>
double SignedFromExcess(const Eigen::Matrix<double, N, 1>& d) {
  return d.cwiseMax(0.0).norm() + std::min(d.maxCoeff(), 0.0);
}

double DistanceToPrismSurface(const Prism& prism, const Eigen::Vector3d& p) {
  const double z_centre = 0.5 * (prism.z_min_m + prism.z_max_m);
  const double z_excess = std::abs(p.z() - z_centre) - 0.5 * (prism.z_max_m - prism.z_min_m);
  const Eigen::Vector2d offset = p.head<2>() - prism.centre_m;
  if (prism.shape == Prism::Shape::kCircle) {
    return std::abs(SignedFromExcess<2>(Eigen::Vector2d(offset.norm() - prism.radius_m, z_excess)));
  }
  const Eigen::Vector2d local = Eigen::Rotation2Dd(-prism.yaw_rad) * offset;
  const Eigen::Vector2d xy_excess = local.cwiseAbs() - prism.half_size_m;
  return std::abs(SignedFromExcess<3>(Eigen::Vector3d(xy_excess.x(), xy_excess.y(), z_excess)));
}

double DistanceToSegment2d(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                           const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double length_sq = ab.squaredNorm();
  const double t = length_sq > 0.0 ? std::clamp((p - a).dot(ab) / length_sq, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

}  // namespace

double DistanceToStaticSurface(const World& world, const Eigen::Vector3d& p_world) {
  double distance = std::min(std::abs(p_world.z()), std::abs(p_world.z() - world.ceiling_height_m));
  for (const Prism& prism : world.prisms) {
    distance = std::min(distance, DistanceToPrismSurface(prism, p_world));
  }
  return distance;
}

double DistanceToPeoplePaths(const World& world, const Eigen::Vector3d& p_world) {
  double distance = std::numeric_limits<double>::infinity();
  const Eigen::Vector2d p_xy = p_world.head<2>();
  for (const Person& person : world.people) {
    if (person.path_m.empty()) continue;
    double to_path_m = (p_xy - person.path_m.front()).norm();
    for (size_t i = 1; i < person.path_m.size(); ++i) {
      to_path_m = std::min(to_path_m, DistanceToSegment2d(p_xy, person.path_m[i - 1], person.path_m[i]));
    }
    const double xy_excess = std::max(0.0, to_path_m - person.radius_m);
    const double z_excess = std::max({0.0, -p_world.z(), p_world.z() - person.height_m});
    distance = std::min(distance, std::hypot(xy_excess, z_excess));
  }
  return distance;
}

}  // namespace sim
}  // namespace fusemap
