#include "fusemap/io/map_writer.h"
#include "fusemap/io/image_file.h"
#include "write_all.h"

#include <cstdio>
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

// World metres to OpenCV pixel coordinates (integer = pixel centre, y down), fixed point.
cv::Point ToPixel(const MapImage& map, const Eigen::Vector2d& p_world) {
  const double u = (p_world.x() - map.origin_m.x()) / map.resolution_m - 0.5;
  const double v = map.height - (p_world.y() - map.origin_m.y()) / map.resolution_m - 0.5;
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
  if (!WriteImageFile(WrapPixels(map), pgm_path, error, {cv::IMWRITE_PXM_BINARY, 1})) return false;
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
  cv::Mat canvas;
  cv::cvtColor(WrapPixels(map), canvas, cv::COLOR_GRAY2BGR);
  if (!trajectory_xy.empty()) {
    std::vector<cv::Point> points;
    points.reserve(trajectory_xy.size());
    for (const Eigen::Vector2d& p : trajectory_xy) points.push_back(ToPixel(map, p));
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
