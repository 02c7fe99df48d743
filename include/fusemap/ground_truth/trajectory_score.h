#ifndef FUSEMAP_GROUND_TRUTH_TRAJECTORY_SCORE_H_
#define FUSEMAP_GROUND_TRUTH_TRAJECTORY_SCORE_H_

#include <Eigen/Core>
#include <string>
#include <vector>

#include "fusemap/common/config_reader.h"
#include "fusemap/eval/absolute_trajectory_error.h"
#include "fusemap/eval/error_statistics.h"
#include "fusemap/eval/relative_pose_error.h"
#include "fusemap/eval/trajectory.h"
#include "fusemap/ground_truth/tag_ground_truth.h"

namespace fusemap {
namespace ground_truth {

struct ScoreOptions {
  // Tag ground truth comes only when a tag is in view, so association is looser than the
  // TUM default.
  double max_time_diff_s = 0.05;
  double rpe_segment_m = 1.0;
  // The trajectory counts as back at its start when the ground truth comes within this radius
  // of its first pose after having been at least twice as far away.
  double loop_radius_m = 0.5;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

// Keys: max_time_diff_s, rpe_segment_m, loop_radius_m.
ScoreOptions ParseScoreOptions(common::ConfigReader& reader);

// A tape-measured distance between two named points and the same distance in the map.
struct MapMeasure {
  std::string from;
  std::string to;
  double measured_m = 0.0;
  Eigen::Vector2d from_map = Eigen::Vector2d::Zero();
  Eigen::Vector2d to_map = Eigen::Vector2d::Zero();
};

struct MeasureCheck {
  std::string from;
  std::string to;
  double measured_m = 0.0;
  double map_m = 0.0;
  double error_m = 0.0;  // map - measured.
};

struct TagResidual {
  int tag_id = -1;
  // |robot position seen through this tag - estimated position at that time|, after the ATE
  // alignment (so it measures local consistency, not the map frame's offset).
  eval::ErrorStatistics position_error_m;
};

struct TrajectoryScore {
  int gt_poses = 0;
  int est_poses = 0;
  int associated = 0;
  double gt_length_m = 0.0;      // Along the associated ground-truth poses.
  eval::AteResult ate;           // Aligned; ate.unaligned_rmse_m without alignment.
  eval::RpeResult rpe;           // Over segments of rpe_segment_m.
  double rpe_trans_per_m = 0.0;  // rpe.trans_m.rmse / rpe_segment_m.
  bool has_loop = false;
  double loop_start_s = 0.0;
  double loop_end_s = 0.0;
  double loop_error_m = 0.0;  // ||(est_end - est_start) - (gt_end - gt_start)||.
  std::vector<TagResidual> tag_residuals;
  std::vector<MeasureCheck> measures;
  // For plots: associated pairs, estimate after alignment.
  std::vector<double> stamps_s;
  std::vector<Eigen::Vector3d> gt_positions;
  std::vector<Eigen::Vector3d> est_positions_aligned;
  std::vector<double> position_errors_m;
};

// Scores an estimated trajectory against tag ground truth. sightings and measures may be empty.
// Returns false with *error when the two trajectories share no stamps within max_time_diff_s.
bool ScoreTrajectory(const eval::Trajectory& gt, const eval::Trajectory& est,
                     const std::vector<TagSighting>& sightings,
                     const std::vector<MapMeasure>& measures, const ScoreOptions& options,
                     TrajectoryScore* score, std::string* error);

}  // namespace ground_truth
}  // namespace fusemap

#endif  // FUSEMAP_GROUND_TRUTH_TRAJECTORY_SCORE_H_
