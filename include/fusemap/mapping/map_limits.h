#ifndef FUSEMAP_MAPPING_MAP_LIMITS_H_
#define FUSEMAP_MAPPING_MAP_LIMITS_H_

#include <Eigen/Core>
#include <cmath>

namespace fusemap {
namespace mapping {

// Geometry of a regular 2D grid. Cell (i, j) covers
// [origin + i * resolution, origin + (i + 1) * resolution) along x (and likewise j along y),
// so origin_m is the outer corner of cell (0, 0), not its centre.
struct MapLimits {
  double resolution_m = 0.05;
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();
  int num_x_cells = 0;
  int num_y_cells = 0;

  Eigen::Array2i GetCellIndex(const Eigen::Vector2f& point_m) const {
    return Eigen::Array2i(
        static_cast<int>(std::floor((point_m.x() - origin_m.x()) / resolution_m)),
        static_cast<int>(std::floor((point_m.y() - origin_m.y()) / resolution_m)));
  }
  Eigen::Vector2d GetCellCenter(const Eigen::Array2i& cell) const {
    return origin_m + resolution_m * Eigen::Vector2d(cell.x() + 0.5, cell.y() + 0.5);
  }
  bool Contains(const Eigen::Array2i& cell) const {
    return cell.x() >= 0 && cell.y() >= 0 && cell.x() < num_x_cells && cell.y() < num_y_cells;
  }
  int FlatIndex(const Eigen::Array2i& cell) const { return cell.y() * num_x_cells + cell.x(); }
};

}  // namespace mapping
}  // namespace fusemap

#endif  // FUSEMAP_MAPPING_MAP_LIMITS_H_
