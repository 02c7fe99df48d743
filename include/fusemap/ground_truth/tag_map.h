#ifndef FUSEMAP_GROUND_TRUTH_TAG_MAP_H_
#define FUSEMAP_GROUND_TRUTH_TAG_MAP_H_

#include <map>

#include "fusemap/common/rigid_transform.h"

namespace fusemap {
namespace ground_truth {

// A tag at a surveyed place. The tag frame has its origin at the tag centre, x to the right
// and y up as the tag is printed (apriltag_to_image's upright view), z out of the printed face;
// a tag lying face-up on the floor with yaw 0 therefore has its axes aligned with the map's.
// size_m is the edge of the black border square (the AprilTag "tag size").
struct SurveyedTag {
  int id = -1;
  double size_m = 0.0;
  common::Rigid3d T_map_tag;
};

// Surveyed tags by id; ids are unique (io/tag_map.h rejects duplicates).
using TagMap = std::map<int, SurveyedTag>;

}  // namespace ground_truth
}  // namespace fusemap

#endif  // FUSEMAP_GROUND_TRUTH_TAG_MAP_H_
