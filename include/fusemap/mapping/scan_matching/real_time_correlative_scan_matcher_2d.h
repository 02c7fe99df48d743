#ifndef FUSEMAP_MAPPING_SCAN_MATCHING_REAL_TIME_CORRELATIVE_SCAN_MATCHER_2D_H_
#define FUSEMAP_MAPPING_SCAN_MATCHING_REAL_TIME_CORRELATIVE_SCAN_MATCHER_2D_H_

#include <string>
#include <vector>

#include "fusemap/common/config_reader.h"
#include "fusemap/common/math.h"
#include "fusemap/common/rigid_transform.h"
#include "fusemap/mapping/probability_grid.h"
#include "fusemap/sensor/sensor_types.h"

namespace fusemap {
namespace mapping {

struct RealTimeCorrelativeScanMatcherOptions2D {
  double linear_search_window_m = 0.1;
  // 8.6 deg, chosen on Intel (config/default.yaml); predictions further off are caught by the
  // wide search at the window's edge (InitialMatchOptions2D).
  double angular_search_window_rad = 0.15;
  double translation_delta_cost_weight = 1e-1;
  double rotation_delta_cost_weight = 1e-1;
  // What a scan point scores in a cell never observed. 0.5, no evidence either way: with
  // kMinProbability (Cartographer's choice, the grid's value there) a scan that sees new
  // space, as in an open hall or at a corridor's end, is pulled by turning its points onto
  // the little that is mapped, and local SLAM takes degree-sized heading errors per step.
  double unknown_probability = 0.5;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

RealTimeCorrelativeScanMatcherOptions2D ParseRealTimeCorrelativeScanMatcherOptions2D(
    common::ConfigReader& reader);

// Exhaustive correlative search (Olson 2009) in a small window around a pose prediction, used
// by local SLAM to give the Ceres matcher a start inside its basin of convergence. Each
// candidate scores the mean grid probability at its points (unknown_probability where the grid
// has seen nothing), damped by its distance from the prediction as in Cartographer.
class RealTimeCorrelativeScanMatcher2D {
 public:
  explicit RealTimeCorrelativeScanMatcher2D(const RealTimeCorrelativeScanMatcherOptions2D& options);

  // `cloud` is in the tracking frame; `initial_pose` and *pose are T_grid_tracking. Returns the
  // best candidate's score (0 for an empty cloud, in which case *pose = initial_pose). If
  // `at_window_edge` is given, it says whether the best candidate lies on the border of the
  // search window (outermost angle or offset): the true optimum may then lie outside it.
  double Match(const common::Rigid2d& initial_pose, const sensor::PointCloud2d& cloud,
               const ProbabilityGrid& grid, common::Rigid2d* pose,
               bool* at_window_edge = nullptr) const;

  // Local SLAM sets it per scan from how well the odometry's heading has predicted.
  void set_rotation_delta_cost_weight(double weight) {
    options_.rotation_delta_cost_weight = weight;
  }

 private:
  RealTimeCorrelativeScanMatcherOptions2D options_;
  // Probability of each stored cell value, unknown_probability for unknown cells.
  std::vector<float> probability_of_value_;
};

}  // namespace mapping
}  // namespace fusemap

#endif  // FUSEMAP_MAPPING_SCAN_MATCHING_REAL_TIME_CORRELATIVE_SCAN_MATCHER_2D_H_
