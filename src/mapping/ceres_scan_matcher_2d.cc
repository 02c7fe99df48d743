#include "fusemap/mapping/scan_matching/ceres_scan_matcher_2d.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/problem.h>

#include <cassert>
#include <cmath>

#include "occupied_space_cost_function_2d.h"

namespace fusemap {
namespace mapping {
namespace {

class TranslationDeltaCostFunctor2D {
 public:
  TranslationDeltaCostFunctor2D(double weight, const Eigen::Vector2d& target_translation)
      : weight_(weight), target_x_m_(target_translation.x()), target_y_m_(target_translation.y()) {}

  template <typename T>
  bool operator()(const T* const pose, T* residual) const {
    residual[0] = weight_ * (pose[0] - target_x_m_);
    residual[1] = weight_ * (pose[1] - target_y_m_);
    return true;
  }

 private:
  const double weight_;
  const double target_x_m_;
  const double target_y_m_;
};

class RotationDeltaCostFunctor2D {
 public:
  RotationDeltaCostFunctor2D(double weight, double target_angle_rad)
      : weight_(weight), target_angle_rad_(target_angle_rad) {}

  template <typename T>
  bool operator()(const T* const pose, T* residual) const {
    // The solver starts at the target angle and moves by far less than pi, so no wrapping.
    residual[0] = weight_ * (pose[2] - target_angle_rad_);
    return true;
  }

 private:
  const double weight_;
  const double target_angle_rad_;
};

}  // namespace

ceres::CostFunction* CreateTranslationDeltaCostFunctor2D(double weight,
                                                         const Eigen::Vector2d& target_translation) {
  return new ceres::AutoDiffCostFunction<TranslationDeltaCostFunctor2D, 2, 3>(
      new TranslationDeltaCostFunctor2D(weight, target_translation));
}

ceres::CostFunction* CreateRotationDeltaCostFunctor2D(double weight, double target_angle_rad) {
  return new ceres::AutoDiffCostFunction<RotationDeltaCostFunctor2D, 1, 3>(
      new RotationDeltaCostFunctor2D(weight, target_angle_rad));
}

void CeresScanMatcherOptions2D::Check(common::OptionChecker* check) const {
  check->Require(occupied_space_weight > 0.0, "occupied_space_weight", "must be > 0");
  check->Require(translation_weight >= 0.0, "translation_weight", "must be >= 0");
  check->Require(rotation_weight >= 0.0, "rotation_weight", "must be >= 0");
  check->Require(max_num_iterations >= 1, "max_num_iterations", "must be >= 1");
  check->Require(num_threads >= 1, "num_threads", "must be >= 1");
  // Compared as the float the grid uses: the YAML value 0.1 is a double just below 0.1f.
  const float unknown = static_cast<float>(unknown_probability);
  check->Require(unknown >= kMinProbability && unknown <= kMaxProbability, "unknown_probability",
                 "must be in [0.1, 0.9]");
}

bool CeresScanMatcherOptions2D::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

CeresScanMatcherOptions2D ParseCeresScanMatcherOptions2D(common::ConfigReader& reader) {
  CeresScanMatcherOptions2D options;
  reader.Get("occupied_space_weight", &options.occupied_space_weight);
  reader.Get("translation_weight", &options.translation_weight);
  reader.Get("rotation_weight", &options.rotation_weight);
  reader.Get("max_num_iterations", &options.max_num_iterations);
  reader.Get("num_threads", &options.num_threads);
  reader.Get("unknown_probability", &options.unknown_probability);
  reader.CheckOptions(options);
  return options;
}

CeresScanMatcher2D::CeresScanMatcher2D(const CeresScanMatcherOptions2D& options)
    : options_(options) {
  std::string error;
  assert(options_.IsValid(&error));
  (void)error;
  solver_options_.use_nonmonotonic_steps = false;
  solver_options_.max_num_iterations = options_.max_num_iterations;
  solver_options_.num_threads = options_.num_threads;
  solver_options_.linear_solver_type = ceres::DENSE_QR;
  solver_options_.minimizer_progress_to_stdout = false;
  solver_options_.logging_type = ceres::SILENT;
}

void CeresScanMatcher2D::Match(const Eigen::Vector2d& target_translation,
                               const common::Rigid2d& initial_pose_estimate,
                               const sensor::PointCloud2d& cloud, const ProbabilityGrid& grid,
                               common::Rigid2d* pose_estimate,
                               ceres::Solver::Summary* summary) const {
  assert(!cloud.empty() && pose_estimate != nullptr && summary != nullptr);
  double pose[3] = {initial_pose_estimate.x(), initial_pose_estimate.y(),
                    initial_pose_estimate.angle_rad()};
  ceres::Problem problem;
  // Dividing by sqrt(N) makes the occupied-space cost a mean, so the priors keep the same
  // relative strength whatever the scan size (as in Cartographer).
  problem.AddResidualBlock(
      CreateOccupiedSpaceCostFunction2D(
          options_.occupied_space_weight / std::sqrt(static_cast<double>(cloud.size())), cloud,
          grid, static_cast<float>(options_.unknown_probability)),
      nullptr, pose);
  problem.AddResidualBlock(
      CreateTranslationDeltaCostFunctor2D(options_.translation_weight, target_translation),
      nullptr, pose);
  problem.AddResidualBlock(
      CreateRotationDeltaCostFunctor2D(options_.rotation_weight, initial_pose_estimate.angle_rad()),
      nullptr, pose);
  ceres::Solve(solver_options_, &problem, summary);
  *pose_estimate = common::Rigid2d(pose[0], pose[1], pose[2]);
}

}  // namespace mapping
}  // namespace fusemap
