#ifndef FUSEMAP_IO_MAP_WRITER_H_
#define FUSEMAP_IO_MAP_WRITER_H_

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace fusemap {
namespace io {

// A rendered occupancy map, greyscale in the ROS map_server convention (negate 0): 0 black =
// occupied, 254 = free, 205 = unknown. Invariant: pixels.size() == width * height.
struct MapImage {
  int width = 0;
  int height = 0;
  double resolution_m = 0.05;  // Edge of one pixel.
  // World position of the lower-left corner of the bottom-left pixel (map_server "origin").
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();
  std::vector<uint8_t> pixels;  // Row-major, row 0 = top (largest y).
};

// Writes `<path_prefix>.pgm` (binary P5) and `<path_prefix>.yaml` for ROS map_server: image
// (the .pgm's file name, relative to the yaml), resolution, origin [x, y, 0], negate 0,
// occupied_thresh 0.65, free_thresh 0.196, mode trinary.
bool WriteMapPgmYaml(const MapImage& map, const std::string& path_prefix, std::string* error);

// Writes a colour PNG of the map with the trajectory (world metres) drawn as an antialiased
// polyline, its start marked by a green and its end by a red circle. A map longer than 4,096
// cells on a side is shrunk by the smallest whole factor that brings it within 4,096 pixels.
bool WriteMapPng(const MapImage& map, const std::vector<Eigen::Vector2d>& trajectory_xy,
                 const std::string& path, std::string* error);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_MAP_WRITER_H_
