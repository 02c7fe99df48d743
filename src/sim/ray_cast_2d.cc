#include "fusemap/sim/ray_cast_2d.h"

#include <cmath>
#include <limits>

namespace fusemap {
namespace sim {
namespace {

// Slab test in the rectangle's frame (Kay & Kajiya 1986).
bool IntersectRectangle(const Prism& prism, const Eigen::Vector2d& origin,
                        const Eigen::Vector2d& direction, FootprintCrossing* crossing) {
  // Most walls are axis-aligned: skip the trigonometry (this runs per pixel when rendering).
  const double c = prism.yaw_rad == 0.0 ? 1.0 : std::cos(prism.yaw_rad);
  const double s = prism.yaw_rad == 0.0 ? 0.0 : std::sin(prism.yaw_rad);
  const Eigen::Vector2d d = origin - prism.centre_m;
  const Eigen::Vector2d o(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
  const Eigen::Vector2d r(c * direction.x() + s * direction.y(),
                          -s * direction.x() + c * direction.y());
  double t_in = -std::numeric_limits<double>::infinity();
  double t_out = std::numeric_limits<double>::infinity();
  int face_in = 0;
  for (int axis = 0; axis < 2; ++axis) {
    const double h = prism.half_size_m[axis];
    if (std::abs(r[axis]) < 1e-12) {
      if (std::abs(o[axis]) > h) return false;
      continue;
    }
    double t0 = (-h - o[axis]) / r[axis];
    double t1 = (h - o[axis]) / r[axis];
    // Entering through the negative side when moving in +axis: faces 2 (-x) or 3 (-y).
    int face0 = r[axis] > 0 ? axis + 2 : axis;
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > t_in) {
      t_in = t0;
      face_in = face0;
    }
    t_out = std::min(t_out, t1);
  }
  if (t_in > t_out || t_out < 0.0) return false;
  crossing->t_in = std::max(0.0, t_in);
  crossing->t_out = t_out;
  crossing->face_in = face_in;
  const Eigen::Vector2d p = o + crossing->t_in * r;
  // Along faces 0/2 the coordinate is local y, along 1/3 local x; offset so u >= 0.
  crossing->u_in_m = (face_in % 2 == 0) ? p.y() + prism.half_size_m.y()
                                        : p.x() + prism.half_size_m.x();
  return true;
}

bool IntersectCircle(const Prism& prism, const Eigen::Vector2d& origin,
                     const Eigen::Vector2d& direction, FootprintCrossing* crossing) {
  const Eigen::Vector2d d = origin - prism.centre_m;
  const double b = d.dot(direction);
  const double c = d.squaredNorm() - prism.radius_m * prism.radius_m;
  const double disc = b * b - c;
  if (disc < 0.0) return false;
  const double root = std::sqrt(disc);
  const double t_out = -b + root;
  if (t_out < 0.0) return false;
  crossing->t_in = std::max(0.0, -b - root);
  crossing->t_out = t_out;
  crossing->face_in = 0;
  const Eigen::Vector2d p = d + crossing->t_in * direction;
  crossing->u_in_m = (std::atan2(p.y(), p.x()) + M_PI) * prism.radius_m;
  return true;
}

}  // namespace

bool IntersectFootprint(const Prism& prism, const Eigen::Vector2d& origin,
                        const Eigen::Vector2d& direction, FootprintCrossing* crossing) {
  return prism.shape == Prism::Shape::kCircle
             ? IntersectCircle(prism, origin, direction, crossing)
             : IntersectRectangle(prism, origin, direction, crossing);
}

double CastRay2d(const std::vector<Prism>& prisms, const Eigen::Vector2d& origin,
                 const Eigen::Vector2d& direction, double z_m, double max_range_m,
                 int* hit_index) {
  double best = max_range_m;
  *hit_index = -1;
  FootprintCrossing crossing;
  for (size_t i = 0; i < prisms.size(); ++i) {
    const Prism& prism = prisms[i];
    if (z_m < prism.z_min_m || z_m > prism.z_max_m) continue;
    if (IntersectFootprint(prism, origin, direction, &crossing) && crossing.t_in < best) {
      best = crossing.t_in;
      *hit_index = static_cast<int>(i);
    }
  }
  return best;
}

}  // namespace sim
}  // namespace fusemap
