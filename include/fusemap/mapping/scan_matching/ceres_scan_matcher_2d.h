#ifndef FUSEMAP_MAPPING_SCAN_MATCHING_CERES_SCAN_MATCHER_2D_H_
#define FUSEMAP_MAPPING_SCAN_MATCHING_CERES_SCAN_MATCHER_2D_H_

#include <ceres/cost_function.h>
#include <ceres/solver.h>

#include <Eigen/Core>
#include <string>

#include "fusemap/common/config_reader.h"
#include "fusemap/common/rigid_transform.h"
#include "fusemap/mapping/probability_grid.h"
#include "fusemap/sensor/sensor_types.h"

namespace fusemap {
namespace mapping {

struct CeresScanMatcherOptions2D {
  // Tuned on Intel and right on every shared log since (config/default.yaml); Cartographer's
  // 1.0 leaves local SLAM closer to the prediction.
  double occupied_space_weight = 10.0;
  double translation_weight = 10.0;
  double rotation_weight = 40.0;
  int max_num_iterations = 20;
  int num_threads = 1;
  // The probability the occupied-space cost reads in never-observed cells (and beyond the
  // grid): 0.5, no evidence, for the reason given at RealTimeCorrelativeScanMatcherOptions2D.
  // Where Ceres matches alone (no correlative search first), 0.1 is better: at 0.5 the cost's
  // slope at the edge of the observed area pushes the scan outward (config/sim.yaml).
  double unknown_probability = 0.5;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

CeresScanMatcherOptions2D ParseCeresScanMatcherOptions2D(common::ConfigReader& reader);

// Residual weight * (t - target_translation) over the pose block [x_m, y_m, angle_rad].
ceres::CostFunction* CreateTranslationDeltaCostFunctor2D(double weight,
                                                         const Eigen::Vector2d& target_translation);
// Residual weight * (angle - target_angle_rad) over the pose block [x_m, y_m, angle_rad].
ceres::CostFunction* CreateRotationDeltaCostFunctor2D(double weight, double target_angle_rad);

// Refines a pose by aligning a point cloud with the smoothed probability grid (Hess et al.
// 2016, Sec. IV-C), with priors keeping the translation near a target (the motion prediction)
// and the angle near the initial estimate.
class CeresScanMatcher2D {
 public:
  explicit CeresScanMatcher2D(const CeresScanMatcherOptions2D& options);

  // `cloud` is in the tracking frame; poses are T_grid_tracking. The cloud must not be empty.
  void Match(const Eigen::Vector2d& target_translation,
             const common::Rigid2d& initial_pose_estimate, const sensor::PointCloud2d& cloud,
             const ProbabilityGrid& grid, common::Rigid2d* pose_estimate,
             ceres::Solver::Summary* summary) const;

 private:
  CeresScanMatcherOptions2D options_;
  ceres::Solver::Options solver_options_;
};

}  // namespace mapping
}  // namespace fusemap

#endif  // FUSEMAP_MAPPING_SCAN_MATCHING_CERES_SCAN_MATCHER_2D_H_
