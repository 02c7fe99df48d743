#include "fusemap/ground_truth/trajectory_score.h"

#include <cmath>
#include <map>

namespace fusemap {
namespace ground_truth {
namespace {

// Index of the pair where the ground truth is back at its start: after first leaving to at least
// 2 * radius, the closest return within radius. -1 when it never returns.
int FindLoopEnd(const std::vector<Eigen::Vector3d>& gt, double radius_m) {
  bool left = false;
  int best = -1;
  double best_distance = radius_m;
  for (size_t i = 1; i < gt.size(); ++i) {
    const double d = (gt[i] - gt[0]).head<2>().norm();
    if (d >= 2.0 * radius_m) left = true;
    if (left && d <= best_distance) {
      best_distance = d;
      best = static_cast<int>(i);
    }
  }
  return best;
}

}  // namespace

void ScoreOptions::Check(common::OptionChecker* check) const {
  check->Require(max_time_diff_s >= 0.0, "max_time_diff_s", "must be >= 0");
  check->Require(rpe_segment_m > 0.0, "rpe_segment_m", "must be > 0");
  check->Require(loop_radius_m > 0.0, "loop_radius_m", "must be > 0");
}

bool ScoreOptions::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

ScoreOptions ParseScoreOptions(common::ConfigReader& reader) {
  ScoreOptions options;
  reader.Get("max_time_diff_s", &options.max_time_diff_s);
  reader.Get("rpe_segment_m", &options.rpe_segment_m);
  reader.Get("loop_radius_m", &options.loop_radius_m);
  reader.CheckOptions(options);
  return options;
}

bool ScoreTrajectory(const eval::Trajectory& gt, const eval::Trajectory& est,
                     const std::vector<TagSighting>& sightings,
                     const std::vector<MapMeasure>& measures, const ScoreOptions& options,
                     TrajectoryScore* score, std::string* error) {
  *score = TrajectoryScore();
  score->gt_poses = static_cast<int>(gt.size());
  score->est_poses = static_cast<int>(est.size());
  const std::vector<eval::PosePair> pairs = eval::AssociateByTime(gt, est, options.max_time_diff_s);
  score->associated = static_cast<int>(pairs.size());
  if (pairs.empty()) {
    *error = "no estimated pose lies within " + std::to_string(options.max_time_diff_s) +
             " s of a ground-truth pose";
    return false;
  }

  eval::AteOptions ate_options;
  ate_options.max_time_diff_s = options.max_time_diff_s;
  score->ate = eval::ComputeAte(gt, est, ate_options);
  const common::Rigid3d& T_gt_est = score->ate.T_gt_est;

  eval::RpeOptions rpe_options;
  rpe_options.delta = options.rpe_segment_m;
  rpe_options.delta_unit = eval::DeltaUnit::kMetres;
  rpe_options.max_time_diff_s = options.max_time_diff_s;
  score->rpe = eval::ComputeRpe(gt, est, rpe_options);
  score->rpe_trans_per_m = score->rpe.trans_m.rmse / options.rpe_segment_m;

  for (size_t i = 0; i < pairs.size(); ++i) {
    const Eigen::Vector3d p_gt = pairs[i].gt.translation();
    const Eigen::Vector3d p_est = T_gt_est * pairs[i].est.translation();
    if (i > 0) score->gt_length_m += (p_gt - score->gt_positions.back()).norm();
    score->stamps_s.push_back(pairs[i].stamp_s);
    score->gt_positions.push_back(p_gt);
    score->est_positions_aligned.push_back(p_est);
    score->position_errors_m.push_back((p_gt - p_est).norm());
  }

  const int loop_end = FindLoopEnd(score->gt_positions, options.loop_radius_m);
  if (loop_end > 0) {
    score->has_loop = true;
    score->loop_start_s = pairs.front().stamp_s;
    score->loop_end_s = pairs[loop_end].stamp_s;
    // Aligned estimate: only the rotation of T_gt_est matters for a difference of positions.
    const Eigen::Vector3d d_est =
        score->est_positions_aligned[loop_end] - score->est_positions_aligned.front();
    const Eigen::Vector3d d_gt = score->gt_positions[loop_end] - score->gt_positions.front();
    score->loop_error_m = (d_est - d_gt).norm();
  }

  std::map<int, std::vector<double>> residuals;
  for (const TagSighting& sighting : sightings) {
    common::Rigid3d T_est;
    if (!eval::LookUpPose(est, sighting.stamp_s, options.max_time_diff_s, &T_est)) continue;
    residuals[sighting.tag_id].push_back(
        (sighting.T_map_base.translation() - T_gt_est * T_est.translation()).norm());
  }
  for (auto& [id, errors] : residuals) {
    score->tag_residuals.push_back({id, eval::ComputeErrorStatistics(std::move(errors))});
  }

  for (const MapMeasure& m : measures) {
    MeasureCheck check;
    check.from = m.from;
    check.to = m.to;
    check.measured_m = m.measured_m;
    check.map_m = (m.to_map - m.from_map).norm();
    check.error_m = check.map_m - check.measured_m;
    score->measures.push_back(check);
  }
  return true;
}

}  // namespace ground_truth
}  // namespace fusemap
