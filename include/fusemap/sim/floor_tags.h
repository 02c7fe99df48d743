#ifndef FUSEMAP_SIM_FLOOR_TAGS_H_
#define FUSEMAP_SIM_FLOOR_TAGS_H_

#include <Eigen/Core>
#include <string>
#include <vector>

#include "fusemap/sim/world.h"

namespace fusemap {
namespace sim {

// The floor tags of a world with their tag36h11 bit patterns (from the apriltag library's own
// code table, apriltag_to_image), indexed by a coarse grid for fast per-pixel lookup.
//
// Tag frame: origin at the tag centre on the floor, x along image columns (left to right), y
// along image rows from bottom to top, z up out of the floor; yaw_rad rotates it about world z.
// So the image as printed is seen upright by a viewer above the floor looking down, with its
// top towards +y of the tag frame. Immutable after construction; safe to share across threads.
class FloorTags {
 public:
  // Fails (false, *error) for ids outside tag36h11 or duplicate ids.
  bool Init(const std::vector<FloorTag>& tags, std::string* error);

  // Reflectance in [0, 1] (0 black, 1 white) at floor point p_world; false if no tag covers it
  // (including its white margin of one cell).
  bool Reflectance(const Eigen::Vector2d& p_world, float* reflectance) const;
  // True if p_world lies within or near (one cell) some tag, for choosing where to supersample.
  bool Near(const Eigen::Vector2d& p_world) const;

  const std::vector<FloorTag>& tags() const { return tags_; }

 private:
  struct Placed {
    double cos_yaw = 1.0;
    double sin_yaw = 0.0;
    double cells_per_m = 1.0;
  };
  // Index of a tag whose outer square (with margin grown by `grow_cells`) covers p, or -1.
  int Find(const Eigen::Vector2d& p_world, double grow_cells, Eigen::Vector2d* p_tag) const;

  static constexpr double kGridM = 1.0;
  std::vector<FloorTag> tags_;
  int total_width_ = 10;                       // Cells across, margin included.
  std::vector<std::vector<uint8_t>> images_;   // total_width_^2 per tag, row-major, 0/255.
  std::vector<Placed> placed_;
  // Dense grid of kGridM cells over the tags' bounding box, listing the tags touching each.
  Eigen::Vector2d grid_origin_m_ = Eigen::Vector2d::Zero();
  int grid_nx_ = 0;
  int grid_ny_ = 0;
  std::vector<std::vector<int>> grid_;
};

}  // namespace sim
}  // namespace fusemap

#endif  // FUSEMAP_SIM_FLOOR_TAGS_H_
