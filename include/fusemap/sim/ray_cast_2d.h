#ifndef FUSEMAP_SIM_RAY_CAST_2D_H_
#define FUSEMAP_SIM_RAY_CAST_2D_H_

#include <Eigen/Core>
#include <vector>

#include "fusemap/sim/world.h"

namespace fusemap {
namespace sim {

// Where a 2D ray origin + t * direction (|direction| = 1, t in metres) crosses a prism's
// footprint: it enters at t_in through face_in and leaves at t_out. u_in_m is the horizontal
// texture coordinate of the entry point along that face.
struct FootprintCrossing {
  double t_in = 0.0;
  double t_out = 0.0;
  int face_in = 0;
  double u_in_m = 0.0;
};

// False if the ray misses the footprint or the footprint lies entirely behind the origin.
// A ray starting inside the footprint gets t_in = 0.
bool IntersectFootprint(const Prism& prism, const Eigen::Vector2d& origin,
                        const Eigen::Vector2d& direction, FootprintCrossing* crossing);

// Distance to the first prism whose height range contains z_m (a planar range finder at
// height z_m), or max_range_m if nothing is hit closer. *hit_index is the prism or -1.
double CastRay2d(const std::vector<Prism>& prisms, const Eigen::Vector2d& origin,
                 const Eigen::Vector2d& direction, double z_m, double max_range_m,
                 int* hit_index);

}  // namespace sim
}  // namespace fusemap

#endif  // FUSEMAP_SIM_RAY_CAST_2D_H_
