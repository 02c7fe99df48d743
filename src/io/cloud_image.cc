#include "fusemap/io/cloud_image.h"
#include "fusemap/io/image_file.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "fusemap/common/math.h"

namespace fusemap {
namespace io {

bool WriteCloudPng(const cloud::ColorCloud& cloud, const CloudImageOptions& options,
                   const std::string& path, std::string* error) {
  const double azimuth = common::DegToRad(options.azimuth_deg);
  const double elevation = common::DegToRad(options.elevation_deg);
  // View frame: u to the viewer's right, v up the image, depth away from the viewer.
  const Eigen::Vector3d toward_viewer(std::cos(elevation) * std::cos(azimuth),
                                      std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
  const Eigen::Vector3d right = Eigen::Vector3d::UnitZ().cross(toward_viewer).normalized();
  const Eigen::Vector3d up = toward_viewer.cross(right);

  std::vector<Eigen::Vector3f> projected;  // u, v, depth
  std::vector<const cloud::ColorPoint*> sources;
  projected.reserve(cloud.size());
  sources.reserve(cloud.size());
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;
  for (const cloud::ColorPoint& point : cloud) {
    const Eigen::Vector3d p(point.x, point.y, point.z);
    if (!p.allFinite() || p.z() > options.clip_above_m) continue;
    const Eigen::Vector2d uv(p.dot(right), p.dot(up));
    lo = lo.cwiseMin(uv);
    hi = hi.cwiseMax(uv);
    projected.emplace_back(uv.x(), uv.y(), -p.dot(toward_viewer));
    sources.push_back(&point);
  }
  if (projected.empty()) {
    *error = path + ": nothing to render (empty cloud, or every point above clip_above_m)";
    return false;
  }
  const int margin = 10;
  const double extent_u = std::max(hi.x() - lo.x(), 1e-3);
  const double extent_v = std::max(hi.y() - lo.y(), 1e-3);
  const double scale = (options.width_px - 2 * margin) / extent_u;
  const int width = options.width_px;
  const int height = std::clamp(static_cast<int>(std::ceil(extent_v * scale)) + 2 * margin, 16, 8192);

  cv::Mat image(height, width, CV_8UC3, cv::Scalar(40, 32, 28));
  std::vector<float> depth(static_cast<size_t>(width) * height, std::numeric_limits<float>::infinity());
  for (size_t i = 0; i < projected.size(); ++i) {
    const int u0 = margin + static_cast<int>((projected[i].x() - lo.x()) * scale);
    const int v0 = height - 1 - margin - static_cast<int>((projected[i].y() - lo.y()) * scale);
    for (int dv = 0; dv < options.splat_px; ++dv) {
      for (int du = 0; du < options.splat_px; ++du) {
        const int u = u0 + du, v = v0 + dv;
        if (u < 0 || v < 0 || u >= width || v >= height) continue;
        float& z = depth[static_cast<size_t>(v) * width + u];
        if (projected[i].z() >= z) continue;
        z = projected[i].z();
        image.at<cv::Vec3b>(v, u) = cv::Vec3b(sources[i]->b, sources[i]->g, sources[i]->r);
      }
    }
  }
  return WriteImageFile(image, path, error);
}

}  // namespace io
}  // namespace fusemap
