#ifndef FUSEMAP_SIM_WORLD_LOADER_H_
#define FUSEMAP_SIM_WORLD_LOADER_H_

#include <string>
#include <vector>

#include "fusemap/sim/world.h"

namespace fusemap {
namespace sim {

// Reads a world description (see data/worlds/hall.yaml for the format: named textures, walls,
// pillars, boxes, floor tags, people, depth dropout zones, robot plan). Returns false with
// "origin:line: message" in *error for malformed or out-of-range input.
bool LoadWorldFromString(const std::string& yaml, const std::string& origin, World* world,
                         std::string* error);
bool LoadWorldFile(const std::string& path, World* world, std::string* error);

// The tag map for scorers: YAML "tags: {id: {x, y, yaw, size_m}}" (metres, radians, world
// frame; size_m is the black square's edge; frame convention in floor_tags.h).
std::string TagMapYaml(const std::vector<FloorTag>& tags);
bool WriteTagMapFile(const std::string& path, const std::vector<FloorTag>& tags, std::string* error);

}  // namespace sim
}  // namespace fusemap

#endif  // FUSEMAP_SIM_WORLD_LOADER_H_
