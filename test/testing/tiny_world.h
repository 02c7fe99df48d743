#ifndef FUSEMAP_TEST_TESTING_TINY_WORLD_H_
#define FUSEMAP_TEST_TESTING_TINY_WORLD_H_

#include <Eigen/Core>
#include <cstdint>

#include "fusemap/cloud/cloud_types.h"
#include "fusemap/sim/world.h"

namespace fusemap {
namespace test_world {

// A 3 m room with one wall at x = 5 (a slab x in [5, 5.2]) and a person walking along y = 2
// from x = 0 to x = 4.
inline sim::World TinyWorld() {
  sim::World world;
  world.ceiling_height_m = 3.0;
  sim::Prism wall;
  wall.centre_m = Eigen::Vector2d(5.1, 0.0);
  wall.half_size_m = Eigen::Vector2d(0.1, 5.0);
  wall.z_max_m = 3.0;
  world.prisms = {wall};
  sim::Person person;
  person.path_m = {Eigen::Vector2d(0.0, 2.0), Eigen::Vector2d(4.0, 2.0)};
  person.radius_m = 0.25;
  person.height_m = 1.8;
  world.people = {person};
  return world;
}

inline cloud::ColorPoint Point(double x, double y, double z) {
  cloud::ColorPoint p(uint8_t{100}, uint8_t{100}, uint8_t{100});
  p.x = static_cast<float>(x);
  p.y = static_cast<float>(y);
  p.z = static_cast<float>(z);
  return p;
}

}  // namespace test_world
}  // namespace fusemap

#endif  // FUSEMAP_TEST_TESTING_TINY_WORLD_H_
