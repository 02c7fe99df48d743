#include "fusemap/sim/world.h"

#include <cmath>

namespace fusemap {
namespace sim {

Prism PersonPrismAt(const Person& person, double stamp_s) {
  Prism prism;
  prism.shape = Prism::Shape::kCircle;
  prism.radius_m = person.radius_m;
  prism.z_min_m = 0.0;
  prism.z_max_m = person.height_m;
  prism.side_textures.fill(person.texture);
  prism.top_texture = person.texture;
  prism.centre_m = person.path_m.empty() ? Eigen::Vector2d::Zero() : person.path_m.front();
  if (person.path_m.size() < 2) return prism;

  double length_m = 0.0;
  for (size_t i = 1; i < person.path_m.size(); ++i) {
    length_m += (person.path_m[i] - person.path_m[i - 1]).norm();
  }
  if (length_m <= 0.0) return prism;
  // Walks there and back: position along the unfolded path of twice the length.
  double s = std::fmod(std::max(0.0, stamp_s) * person.speed_mps, 2.0 * length_m);
  if (s > length_m) s = 2.0 * length_m - s;
  for (size_t i = 1; i < person.path_m.size(); ++i) {
    const Eigen::Vector2d segment = person.path_m[i] - person.path_m[i - 1];
    const double segment_length_m = segment.norm();
    if (s <= segment_length_m || i + 1 == person.path_m.size()) {
      const double f = segment_length_m > 0.0 ? std::min(1.0, s / segment_length_m) : 0.0;
      prism.centre_m = person.path_m[i - 1] + f * segment;
      break;
    }
    s -= segment_length_m;
  }
  return prism;
}

std::vector<Prism> PrismsAt(const World& world, double stamp_s) {
  std::vector<Prism> prisms = world.prisms;
  prisms.reserve(world.prisms.size() + world.people.size());
  for (const Person& person : world.people) prisms.push_back(PersonPrismAt(person, stamp_s));
  return prisms;
}

}  // namespace sim
}  // namespace fusemap
