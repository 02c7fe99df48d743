#include "depth_carver.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace fusemap {
namespace cloud {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

}  // namespace

DepthCarver::DepthCarver(const DepthCarverOptions& options) : options_(options) {
  assert(options.pixel_stride >= 1 && options.window_cells >= 0);
}

void DepthCarver::SetImage(const sensor::PinholeIntrinsics& intrinsics,
                           const std::vector<uint16_t>& depth_mm) {
  intrinsics_ = intrinsics;
  const int stride = options_.pixel_stride;
  cells_x_ = (intrinsics.width + stride - 1) / stride;
  cells_y_ = (intrinsics.height + stride - 1) / stride;
  const size_t pixels = static_cast<size_t>(intrinsics.width) * intrinsics.height;
  if (cells_x_ <= 0 || cells_y_ <= 0 || depth_mm.size() < pixels) {
    cells_x_ = cells_y_ = 0;
    return;
  }
  cell_min_m_.assign(static_cast<size_t>(cells_x_) * cells_y_, kInf);
  for (int row = 0; row < intrinsics.height; ++row) {
    const uint16_t* depth_row = depth_mm.data() + static_cast<size_t>(row) * intrinsics.width;
    float* cells = cell_min_m_.data() + static_cast<size_t>(row / stride) * cells_x_;
    for (int col = 0; col < intrinsics.width; ++col) {
      if (depth_row[col] == 0) continue;
      float& cell = cells[col / stride];
      cell = std::min(cell, 1e-3f * depth_row[col]);
    }
  }
  // Separable minimum filter over the window.
  const int w = options_.window_cells;
  std::vector<float> rows_min(cell_min_m_.size(), kInf);
  for (int y = 0; y < cells_y_; ++y) {
    for (int x = 0; x < cells_x_; ++x) {
      float m = kInf;
      for (int dx = std::max(0, x - w); dx <= std::min(cells_x_ - 1, x + w); ++dx) {
        m = std::min(m, cell_min_m_[static_cast<size_t>(y) * cells_x_ + dx]);
      }
      rows_min[static_cast<size_t>(y) * cells_x_ + x] = m;
    }
  }
  window_min_m_.assign(cell_min_m_.size(), kInf);
  for (int y = 0; y < cells_y_; ++y) {
    for (int x = 0; x < cells_x_; ++x) {
      float m = kInf;
      for (int dy = std::max(0, y - w); dy <= std::min(cells_y_ - 1, y + w); ++dy) {
        m = std::min(m, rows_min[static_cast<size_t>(dy) * cells_x_ + x]);
      }
      window_min_m_[static_cast<size_t>(y) * cells_x_ + x] = m;
    }
  }
  // Inward normals of the planes through the optical centre and the image borders.
  const float left = static_cast<float>(-intrinsics.cx / intrinsics.fx);
  const float right = static_cast<float>((intrinsics.width - 1 - intrinsics.cx) / intrinsics.fx);
  const float top = static_cast<float>(-intrinsics.cy / intrinsics.fy);
  const float bottom = static_cast<float>((intrinsics.height - 1 - intrinsics.cy) / intrinsics.fy);
  side_normals_ = {Eigen::Vector3f(1.f, 0.f, -left).normalized(),
                   Eigen::Vector3f(-1.f, 0.f, right).normalized(),
                   Eigen::Vector3f(0.f, 1.f, -top).normalized(),
                   Eigen::Vector3f(0.f, -1.f, bottom).normalized()};
}

bool DepthCarver::SeesThrough(const Eigen::Vector3f& p_depth) const {
  const float z = p_depth.z();
  if (cells_x_ == 0 || !(z >= options_.min_range_m) || z > options_.max_range_m) return false;
  const double u = intrinsics_.fx * p_depth.x() / z + intrinsics_.cx;
  const double v = intrinsics_.fy * p_depth.y() / z + intrinsics_.cy;
  const long col = std::lround(u);
  const long row = std::lround(v);
  if (col < 0 || row < 0 || col >= intrinsics_.width || row >= intrinsics_.height) return false;
  const float nearest_m =
      window_min_m_[static_cast<size_t>(row / options_.pixel_stride) * cells_x_ +
                    col / options_.pixel_stride];
  if (nearest_m == kInf) return z < options_.no_return_carve_m;
  const float margin_m = std::max(static_cast<float>(options_.margin_m),
                                  static_cast<float>(options_.margin_range_fraction) * z);
  return z < nearest_m - margin_m;
}

}  // namespace cloud
}  // namespace fusemap
