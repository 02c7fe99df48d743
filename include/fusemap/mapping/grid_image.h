#ifndef FUSEMAP_MAPPING_GRID_IMAGE_H_
#define FUSEMAP_MAPPING_GRID_IMAGE_H_

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "fusemap/common/rigid_transform.h"
#include "fusemap/mapping/probability_grid.h"

namespace fusemap {
namespace mapping {

// An 8-bit greyscale map image in map_server conventions: row-major, row 0 is the top (max y),
// origin_m is the map-frame position of the image's lower-left corner (like map_server's
// YAML `origin`). Pixel values: kUnknownPixel, kFreePixel, kOccupiedPixel, or a grey between.
struct GridImage {
  int width = 0;
  int height = 0;
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();
  double resolution_m = 0.05;
  std::vector<uint8_t> pixels;

  uint8_t at(int row, int col) const { return pixels[static_cast<size_t>(row) * width + col]; }
};

constexpr uint8_t kUnknownPixel = 205;
constexpr uint8_t kFreePixel = 254;
constexpr uint8_t kOccupiedPixel = 0;
constexpr float kFreeBelowProbability = 0.35f;
constexpr float kOccupiedAboveProbability = 0.65f;

// Below 0.35 free, above 0.65 occupied; in between round(255 * (1 - p)), so map_server's
// reading p = (255 - pixel) / 255 recovers the probability and, with its usual thresholds
// (free 0.196, occupied 0.65), classes the cell as unknown.
uint8_t ProbabilityToPixel(float probability);

// A grid and where it lies: T_map_grid maps grid-frame (for submaps: local-frame) coordinates
// into the map frame. For a submap whose pose was optimised,
// T_map_grid = T_map_submap_optimised * T_local_submap.inverse().
using PlacedGrid = std::pair<common::Rigid2d, const ProbabilityGrid*>;

// Renders the known parts of all grids into one image at `resolution_m`, covering their
// union. Each pixel samples the nearest cell of each grid at its centre and keeps the value
// most confident about free or occupied (largest |p - 0.5|). Empty image if nothing is known.
GridImage RenderMap(const std::vector<PlacedGrid>& grids, double resolution_m);

// A grid fetched only while it is measured and drawn (a compacted submap inflates a copy per
// fetch), and its T_map_grid as in PlacedGrid.
struct GridSource {
  common::Rigid2d T_map_grid;
  std::function<std::shared_ptr<const ProbabilityGrid>()> fetch;
};
// The same image, holding one grid at a time: each is fetched twice (bounds, then pixels).
GridImage RenderMap(const std::vector<GridSource>& grids, double resolution_m);

// One grid in its own frame at its own resolution.
GridImage RenderGrid(const ProbabilityGrid& grid);

}  // namespace mapping
}  // namespace fusemap

#endif  // FUSEMAP_MAPPING_GRID_IMAGE_H_
