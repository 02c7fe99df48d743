#ifndef FUSEMAP_IO_TAG_MAP_H_
#define FUSEMAP_IO_TAG_MAP_H_

#include <string>
#include <vector>

#include "fusemap/ground_truth/tag_ground_truth.h"
#include "fusemap/ground_truth/tag_map.h"
#include "fusemap/ground_truth/trajectory_score.h"

namespace fusemap {
namespace io {

// Files of the AprilTag survey: where the tags are, tape measures between named points, and the
// per-tag sightings the ground-truth pass found. Readers return false with `file:line: reason`.

// Tag map YAML:
//   tag_size_m: 0.16          # optional default for tags without size_m
//   tags:
//     - {id: 0, x_m: 0.3, y_m: 0.3, yaw_deg: 0}
//     - {id: 1, x_m: 0.9, y_m: 0.3, z_m: 0.0, roll_deg: 0, pitch_deg: 0, yaw_deg: 90, size_m: 0.15}
// Rotation = Rz(yaw) Ry(pitch) Rx(roll) of the tag frame of ground_truth/tag_map.h; a tag face-up
// on the floor has roll = pitch = 0. A tag's size is size_m, else the file's tag_size_m, else
// default_tag_size_m (<= 0: a size is required). Duplicate ids and unknown keys are errors.
bool ReadTagMapFile(const std::string& path, double default_tag_size_m,
                    ground_truth::TagMap* tag_map, std::string* error);
bool WriteTagMapFile(const std::string& path, const ground_truth::TagMap& tag_map,
                     std::string* error);

// Measures YAML:
//   points: {door: [1.20, 3.40], pillar: [7.85, 3.38]}   # read off the SLAM map, metres
//   measures:
//     - {from: door, to: pillar, distance_m: 6.62}       # tape-measured
bool ReadMeasuresFile(const std::string& path, std::vector<ground_truth::MapMeasure>* measures,
                      std::string* error);

// Sightings text: `stamp_s tag_id x y z qx qy qz qw` per line (T_map_base seen through the tag),
// '#' comments.
bool WriteTagSightingsFile(const std::string& path,
                           const std::vector<ground_truth::TagSighting>& sightings,
                           std::string* error);
bool ReadTagSightingsFile(const std::string& path,
                          std::vector<ground_truth::TagSighting>* sightings, std::string* error);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_TAG_MAP_H_
