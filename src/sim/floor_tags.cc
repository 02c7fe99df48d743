#include "fusemap/sim/floor_tags.h"

#include <apriltag/apriltag.h>
#include <apriltag/tag36h11.h>

#include <cmath>
#include <set>

namespace fusemap {
namespace sim {

bool FloorTags::Init(const std::vector<FloorTag>& tags, std::string* error) {
  apriltag_family_t* family = tag36h11_create();
  tags_ = tags;
  images_.clear();
  placed_.clear();
  grid_.clear();
  grid_nx_ = grid_ny_ = 0;
  total_width_ = family->total_width;
  std::set<int> seen;
  bool ok = true;
  for (size_t i = 0; i < tags_.size() && ok; ++i) {
    const FloorTag& tag = tags_[i];
    if (tag.id < 0 || tag.id >= static_cast<int>(family->ncodes)) {
      *error = "tag id " + std::to_string(tag.id) + " is not in tag36h11 (0.." +
               std::to_string(family->ncodes - 1) + ")";
      ok = false;
      break;
    }
    if (!seen.insert(tag.id).second) {
      *error = "duplicate tag id " + std::to_string(tag.id);
      ok = false;
      break;
    }
    image_u8_t* image = apriltag_to_image(family, tag.id);
    std::vector<uint8_t> pixels(total_width_ * total_width_);
    for (int r = 0; r < total_width_; ++r) {
      for (int c = 0; c < total_width_; ++c) pixels[r * total_width_ + c] = image->buf[r * image->stride + c];
    }
    image_u8_destroy(image);
    images_.push_back(std::move(pixels));
    placed_.push_back(Placed{std::cos(tag.yaw_rad), std::sin(tag.yaw_rad),
                             family->width_at_border / tag.size_m});
  }
  if (ok && !tags_.empty()) {
    // Register each tag in every grid cell its (grown) outer square's bounding box touches.
    std::vector<double> reach(tags_.size());
    Eigen::Vector2d lo(1e18, 1e18), hi(-1e18, -1e18);
    for (size_t i = 0; i < tags_.size(); ++i) {
      reach[i] = 0.5 * std::sqrt(2.0) * (total_width_ + 2) / placed_[i].cells_per_m;
      const Eigen::Vector2d c(tags_[i].x_m, tags_[i].y_m);
      lo = lo.cwiseMin(c - Eigen::Vector2d::Constant(reach[i]));
      hi = hi.cwiseMax(c + Eigen::Vector2d::Constant(reach[i]));
    }
    grid_origin_m_ = lo;
    grid_nx_ = static_cast<int>(std::floor((hi.x() - lo.x()) / kGridM)) + 1;
    grid_ny_ = static_cast<int>(std::floor((hi.y() - lo.y()) / kGridM)) + 1;
    grid_.assign(static_cast<size_t>(grid_nx_) * grid_ny_, {});
    for (size_t i = 0; i < tags_.size(); ++i) {
      const int x0 = static_cast<int>((tags_[i].x_m - reach[i] - lo.x()) / kGridM);
      const int x1 = static_cast<int>((tags_[i].x_m + reach[i] - lo.x()) / kGridM);
      const int y0 = static_cast<int>((tags_[i].y_m - reach[i] - lo.y()) / kGridM);
      const int y1 = static_cast<int>((tags_[i].y_m + reach[i] - lo.y()) / kGridM);
      for (int ix = x0; ix <= std::min(x1, grid_nx_ - 1); ++ix) {
        for (int iy = y0; iy <= std::min(y1, grid_ny_ - 1); ++iy) {
          grid_[ix * grid_ny_ + iy].push_back(static_cast<int>(i));
        }
      }
    }
  }
  tag36h11_destroy(family);
  return ok;
}

int FloorTags::Find(const Eigen::Vector2d& p_world, double grow_cells, Eigen::Vector2d* p_tag) const {
  const Eigen::Vector2d g = (p_world - grid_origin_m_) / kGridM;
  if (!(g.x() >= 0.0 && g.y() >= 0.0 && g.x() < grid_nx_ && g.y() < grid_ny_)) return -1;
  for (int index : grid_[static_cast<int>(g.x()) * grid_ny_ + static_cast<int>(g.y())]) {
    const FloorTag& tag = tags_[index];
    const Placed& placed = placed_[index];
    const Eigen::Vector2d d = p_world - Eigen::Vector2d(tag.x_m, tag.y_m);
    // Coordinates in cells (black square = width_at_border cells).
    const Eigen::Vector2d local(
        (placed.cos_yaw * d.x() + placed.sin_yaw * d.y()) * placed.cells_per_m,
        (-placed.sin_yaw * d.x() + placed.cos_yaw * d.y()) * placed.cells_per_m);
    const double half = 0.5 * total_width_ + grow_cells;
    if (std::abs(local.x()) < half && std::abs(local.y()) < half) {
      *p_tag = local;
      return index;
    }
  }
  return -1;
}

bool FloorTags::Reflectance(const Eigen::Vector2d& p_world, float* reflectance) const {
  Eigen::Vector2d local;
  const int index = Find(p_world, 0.0, &local);
  if (index < 0) return false;
  const int col = std::min(total_width_ - 1, static_cast<int>(std::floor(local.x() + 0.5 * total_width_)));
  const int row = std::min(total_width_ - 1, static_cast<int>(std::floor(0.5 * total_width_ - local.y())));
  *reflectance = images_[index][row * total_width_ + col] / 255.f;
  return true;
}

bool FloorTags::Near(const Eigen::Vector2d& p_world) const {
  Eigen::Vector2d local;
  return Find(p_world, 1.0, &local) >= 0;
}

}  // namespace sim
}  // namespace fusemap
