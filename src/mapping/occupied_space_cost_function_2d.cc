#include "occupied_space_cost_function_2d.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/cubic_interpolation.h>

#include <Eigen/Core>
#include <cassert>

namespace fusemap {
namespace mapping {
namespace {

// Presents a ProbabilityGrid to ceres::BiCubicInterpolator as a row-major (row = y cell,
// column = x cell) array of correspondence costs 1 - p. Never-observed cells, and reads outside
// the grid, give 1 - unknown_probability, so the interpolant stays defined (and flat) beyond
// the map's edge.
class GridArrayAdapter {
 public:
  enum { DATA_DIMENSION = 1 };

  GridArrayAdapter(const ProbabilityGrid& grid, float unknown_probability)
      : grid_(grid), unknown_probability_(unknown_probability) {}

  void GetValue(int row, int column, double* value) const {
    *value = 1.0 - static_cast<double>(
                       grid_.GetProbabilityOr(Eigen::Array2i(column, row), unknown_probability_));
  }

 private:
  const ProbabilityGrid& grid_;
  const float unknown_probability_;
};

// Samples this many cells beyond the grid are all unknown, so the bicubic interpolant (4 x 4
// samples) is flat there; clamping to this band changes no cost and keeps a far or non-finite
// pose from overflowing the interpolator's integer sample index.
constexpr double kOutsideCells = 4.0;

template <typename T>
T ClampToBand(const T& value, int num_cells) {
  if (!(value >= T(-kOutsideCells))) return T(-kOutsideCells);  // NaN too
  if (value > T(num_cells + kOutsideCells)) return T(num_cells + kOutsideCells);
  return value;
}

class OccupiedSpaceCostFunctor2D {
 public:
  OccupiedSpaceCostFunctor2D(double scaling_factor, const sensor::PointCloud2d& cloud,
                             const ProbabilityGrid& grid, float unknown_probability)
      : scaling_factor_(scaling_factor),
        cloud_(cloud),
        grid_(grid),
        adapter_(grid, unknown_probability),
        interpolator_(adapter_) {}

  OccupiedSpaceCostFunctor2D(const OccupiedSpaceCostFunctor2D&) = delete;
  OccupiedSpaceCostFunctor2D& operator=(const OccupiedSpaceCostFunctor2D&) = delete;

  template <typename T>
  bool operator()(const T* const pose, T* residual) const {
    using std::cos;
    using std::sin;
    const T cos_a = cos(pose[2]);
    const T sin_a = sin(pose[2]);
    const MapLimits& limits = grid_.limits();
    const double inv_resolution = 1.0 / limits.resolution_m;
    for (size_t i = 0; i < cloud_.size(); ++i) {
      const T px = T(static_cast<double>(cloud_[i].x()));
      const T py = T(static_cast<double>(cloud_[i].y()));
      const T x_m = cos_a * px - sin_a * py + pose[0];
      const T y_m = sin_a * px + cos_a * py + pose[1];
      // Sample (row j, column i) sits at the centre of cell (i, j), hence the half-cell shift.
      const T column = ClampToBand((x_m - limits.origin_m.x()) * inv_resolution - 0.5, limits.num_x_cells);
      const T row = ClampToBand((y_m - limits.origin_m.y()) * inv_resolution - 0.5, limits.num_y_cells);
      interpolator_.Evaluate(row, column, &residual[i]);
      residual[i] = scaling_factor_ * residual[i];
    }
    return true;
  }

 private:
  const double scaling_factor_;
  const sensor::PointCloud2d& cloud_;
  const ProbabilityGrid& grid_;
  const GridArrayAdapter adapter_;
  const ceres::BiCubicInterpolator<GridArrayAdapter> interpolator_;
};

}  // namespace

ceres::CostFunction* CreateOccupiedSpaceCostFunction2D(double scaling_factor,
                                                       const sensor::PointCloud2d& cloud,
                                                       const ProbabilityGrid& grid,
                                                       float unknown_probability) {
  assert(!cloud.empty());
  return new ceres::AutoDiffCostFunction<OccupiedSpaceCostFunctor2D, ceres::DYNAMIC, 3>(
      new OccupiedSpaceCostFunctor2D(scaling_factor, cloud, grid, unknown_probability),
      static_cast<int>(cloud.size()));
}

}  // namespace mapping
}  // namespace fusemap
