#ifndef FUSEMAP_SIM_SURFACE_DISTANCE_H_
#define FUSEMAP_SIM_SURFACE_DISTANCE_H_

#include <Eigen/Core>

#include "fusemap/sim/world.h"

namespace fusemap {
namespace sim {

// Ground truth for evaluating 3D maps against the simulated world (world frame, metres).

// Distance from p_world to the nearest static surface: the floor plane z = 0, the ceiling
// plane, and the boundary of every static prism (sides, top and bottom). Points inside a
// prism get their distance to its nearest face.
double DistanceToStaticSurface(const World& world, const Eigen::Vector3d& p_world);

// Distance from p_world to the volume every person sweeps while walking: their path polyline
// inflated by their radius, from z = 0 to their height. Zero inside; +infinity without people.
double DistanceToPeoplePaths(const World& world, const Eigen::Vector3d& p_world);

}  // namespace sim
}  // namespace fusemap

#endif  // FUSEMAP_SIM_SURFACE_DISTANCE_H_
