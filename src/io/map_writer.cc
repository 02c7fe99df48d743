#include "fusemap/io/map_writer.h"
#include "fusemap/io/image_file.h"
#include "write_all.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace fusemap {
namespace io {
namespace {

// cv::polylines works in fixed point with this many fractional bits, so sub-pixel positions
// are kept.
constexpr int kShiftBits = 4;
constexpr double kShiftScale = 1 << kShiftBits;
// map.png is a picture to look at: a campus-sized map (7,000 x 5,000 cells) is shrunk to this
// many pixels on its longer side, so its colour canvas does not cost three bytes per cell.
// map.pgm keeps every cell.
constexpr int kMaxPngSidePx = 4096;

bool CheckMap(const MapImage& map, std::string* error) {
  if (map.width <= 0 || map.height <= 0 ||
      map.pixels.size() != static_cast<size_t>(map.width) * static_cast<size_t>(map.height)) {
    *error = "map image is empty or its pixel count does not match width x height";
    return false;
  }
  if (!(map.resolution_m > 0.0)) {
    *error = "map resolution must be > 0";
    return false;
  }
  return true;
}

cv::Mat WrapPixels(const MapImage& map) {
  // cv::Mat does not take const data; the wrapper is only read (and cloned before drawing).
  return cv::Mat(map.height, map.width, CV_8UC1, const_cast<uint8_t*>(map.pixels.data()));
}

// World metres to OpenCV pixel coordinates (integer = pixel centre, y down), fixed point, in
// an image of the map shrunk to `size` pixels.
cv::Point ToPixel(const MapImage& map, const cv::Size& size, const Eigen::Vector2d& p_world) {
  const double cells_x = (p_world.x() - map.origin_m.x()) / map.resolution_m;
  const double cells_y = (p_world.y() - map.origin_m.y()) / map.resolution_m;
  const double u = cells_x * size.width / map.width - 0.5;
  const double v = (map.height - cells_y) * size.height / map.height - 0.5;
  return cv::Point(cvRound(u * kShiftScale), cvRound(v * kShiftScale));
}

std::string BaseName(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace

bool WriteMapPgmYaml(const MapImage& map, const std::string& path_prefix, std::string* error) {
  if (!CheckMap(map, error)) return false;
  const std::string pgm_path = path_prefix + ".pgm";
  const std::string yaml_path = path_prefix + ".yaml";
  // Binary PGM is this header and the pixels as they are: written from the map's own buffer,
  // since an encoder's copies of a campus-sized map cost tens of megabytes.
  const std::string header =
      "P5\n" + std::to_string(map.width) + " " + std::to_string(map.height) + "\n255\n";
  if (!WriteFileAtomically(pgm_path,
                           {{header.data(), header.size()}, {map.pixels.data(), map.pixels.size()}},
                           error)) {
    return false;
  }
  char yaml[512];
  std::snprintf(yaml, sizeof(yaml),
                "image: %s\nresolution: %.9g\norigin: [%.9g, %.9g, 0.0]\nnegate: 0\n"
                "occupied_thresh: 0.65\nfree_thresh: 0.196\nmode: trinary\n",
                BaseName(pgm_path).c_str(), map.resolution_m, map.origin_m.x(), map.origin_m.y());
  return WriteFileAtomically(yaml_path, yaml, error);
}

bool WriteMapPng(const MapImage& map, const std::vector<Eigen::Vector2d>& trajectory_xy,
                 const std::string& path, std::string* error) {
  if (!CheckMap(map, error)) return false;
  const int shrink = (std::max(map.width, map.height) + kMaxPngSidePx - 1) / kMaxPngSidePx;
  const cv::Size size((map.width + shrink - 1) / shrink, (map.height + shrink - 1) / shrink);
  cv::Mat canvas;
  if (shrink == 1) {
    cv::cvtColor(WrapPixels(map), canvas, cv::COLOR_GRAY2BGR);
  } else {
    cv::Mat small;
    cv::resize(WrapPixels(map), small, size, 0.0, 0.0, cv::INTER_AREA);
    cv::cvtColor(small, canvas, cv::COLOR_GRAY2BGR);
  }
  if (!trajectory_xy.empty()) {
    std::vector<cv::Point> points;
    points.reserve(trajectory_xy.size());
    for (const Eigen::Vector2d& p : trajectory_xy) points.push_back(ToPixel(map, size, p));
    const cv::Scalar kLineBgr(255, 90, 0);
    cv::polylines(canvas, points, /*isClosed=*/false, kLineBgr, 1, cv::LINE_AA, kShiftBits);
    const int radius = 4 << kShiftBits;
    cv::circle(canvas, points.front(), radius, cv::Scalar(0, 170, 0), 2, cv::LINE_AA, kShiftBits);
    cv::circle(canvas, points.back(), radius, cv::Scalar(0, 0, 220), 2, cv::LINE_AA, kShiftBits);
  }
  return WriteImageFile(canvas, path, error);
}

}  // namespace io
}  // namespace fusemap
