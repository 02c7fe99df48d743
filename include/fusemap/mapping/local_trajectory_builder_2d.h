#ifndef FUSEMAP_MAPPING_LOCAL_TRAJECTORY_BUILDER_2D_H_
#define FUSEMAP_MAPPING_LOCAL_TRAJECTORY_BUILDER_2D_H_

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fusemap/common/config_reader.h"
#include "fusemap/common/rigid_transform.h"
#include "fusemap/mapping/adaptive_rotation_prior.h"
#include "fusemap/mapping/motion_filter.h"
#include "fusemap/mapping/pose_extrapolator_2d.h"
#include "fusemap/mapping/scan_matching/ceres_scan_matcher_2d.h"
#include "fusemap/mapping/scan_matching/initial_match_2d.h"
#include "fusemap/mapping/scan_matching/real_time_correlative_scan_matcher_2d.h"
#include "fusemap/mapping/submap_2d.h"
#include "fusemap/sensor/range_data_builder.h"
#include "fusemap/sensor/sensor_types.h"
#include "fusemap/sensor/voxel_filter.h"

namespace fusemap {
namespace mapping {

struct LocalTrajectoryBuilderOptions2D {
  // Pose of the laser on the robot base (the tracking frame).
  common::Rigid2d T_tracking_laser;
  sensor::RangeGateOptions range_gate;
  float voxel_filter_size_m = 0.025f;
  sensor::AdaptiveVoxelFilterOptions adaptive_voxel_filter;
  // The node's cloud for loop-closure search: fewer points, since branch-and-bound cost grows
  // with them (Cartographer's loop_closure_adaptive_voxel_filter).
  sensor::AdaptiveVoxelFilterOptions loop_closure_adaptive_voxel_filter;
  // Scans with fewer returns than this are counted and skipped: too little to match against.
  int min_num_returns = 10;
  // Branch and bound in a large window before the fine matchers, for logs whose prediction
  // can be metres off (no odometry, sparse scans).
  InitialMatchOptions2D initial_branch_and_bound_match;
  bool use_online_correlative_scan_matching = true;
  RealTimeCorrelativeScanMatcherOptions2D real_time_correlative_scan_matcher;
  // Sets the real-time match's rotation_delta_cost_weight from the heading corrections
  // recent matches made to the prediction (see AdaptiveRotationPrior).
  AdaptiveRotationPriorOptions adaptive_rotation_prior;
  CeresScanMatcherOptions2D ceres_scan_matcher;
  MotionFilterOptions motion_filter;
  SubmapsOptions submaps;
  bool use_odometry = true;
  bool use_imu = true;
  double pose_queue_duration_s = 0.5;

  LocalTrajectoryBuilderOptions2D();
  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

// Keys: T_tracking_laser [x_m, y_m, yaw_rad], range_gate, voxel_filter_size_m,
// adaptive_voxel_filter, loop_closure_adaptive_voxel_filter, min_num_returns,
// initial_branch_and_bound_match, use_online_correlative_scan_matching,
// real_time_correlative_scan_matcher, adaptive_rotation_prior, ceres_scan_matcher,
// motion_filter, submaps,
// use_odometry, use_imu, pose_queue_duration_s.
LocalTrajectoryBuilderOptions2D ParseLocalTrajectoryBuilderOptions2D(common::ConfigReader& reader);

struct LocalTrajectoryBuilderState2D;

// Local SLAM (Hess et al. 2016, Sec. IV): each scan is matched against the older active
// submap starting from the extrapolated pose, then inserted into both active submaps unless
// the motion filter finds it too close to the last inserted one. Poses are T_local_tracking
// in the drifting local frame; global SLAM corrects them.
class LocalTrajectoryBuilder2D {
 public:
  struct InsertionResult {
    // The data of the new trajectory node, in the tracking frame, for loop closure.
    sensor::PointCloud2d filtered_cloud;
    // The submaps the scan went into, oldest first (the front one may have just finished).
    std::vector<std::shared_ptr<const Submap2D>> insertion_submaps;
  };
  struct MatchingResult {
    double stamp_s = 0.0;
    common::Rigid2d T_local_tracking;
    double match_score = 0.0;  // of the correlative search; 0 when it did not run
    std::optional<InsertionResult> insertion;  // empty if the motion filter dropped the scan
  };
  struct Stats {
    int scans = 0;
    int too_few_returns = 0;
    int out_of_order = 0;
    int inserted = 0;
    int odometry_rejected = 0;
    int imu_rejected = 0;
    // Scans whose initial branch-and-bound match found no answer (the prediction was kept):
    // none above min_score or, at the window's edge, none that could have been taken. Not in
    // checkpoints: map_builder_state_codec predates it.
    int initial_match_rejected = 0;
    // With initial_branch_and_bound_match.only_at_window_edge: scans whose real-time match
    // ended on its window's border (the wide search ran), and those whose pose came from the
    // wide search. Not in checkpoints either.
    int window_edge_matches = 0;
    int wide_matches_taken = 0;
    // Scans whose extrapolated pose jumped absurdly (kMaxPredictedJumpM) from the last pose,
    // matched from a prediction without odometry instead; scans whose data no submap could hold (a pose too
    // far away: ProbabilityGrid::kMaxCells), not inserted. Not in checkpoints either.
    int absurd_predictions = 0;
    int insertions_refused = 0;
  };
  // Far beyond any robot's motion between two scans: a prediction further than this from the
  // last pose comes from corrupt odometry or IMU data.
  static constexpr double kMaxPredictedJumpM = 100.0;
  // How much more than a wide search's answer scores itself the real-time match started from
  // it may score: it searches the same lattice of poses a little further, from cells
  // discretised around another centre. On the log benchmark it added at most 0.018 to an
  // answer that was taken. The wide search looks only for answers that could be taken (see
  // MatchWidenedAtWindowEdge), less this margin.
  static constexpr double kRematchScoreMargin = 0.03;

  explicit LocalTrajectoryBuilder2D(const LocalTrajectoryBuilderOptions2D& options);

  LocalTrajectoryBuilder2D(const LocalTrajectoryBuilder2D&) = delete;
  LocalTrajectoryBuilder2D& operator=(const LocalTrajectoryBuilder2D&) = delete;

  void AddOdometry(const sensor::OdometryData& odometry);
  void AddImu(const sensor::ImuData& imu);
  // The stream's time base was reset (sensor::StampFilter): odometry before and after it need
  // not be continuous (a looping log player restarts it), so motion across it is not taken
  // from odometry (PoseExtrapolator2D::ForgetMotion).
  void OnTimeReset() { extrapolator_.ForgetMotion(); }
  // Empty if the scan was unusable (too few returns, older than the previous scan).
  std::optional<MatchingResult> AddScan(const sensor::LaserScan& scan);

  const Stats& stats() const { return stats_; }
  std::vector<std::shared_ptr<const Submap2D>> active_submaps() const {
    return active_submaps_.submaps();
  }

  // The state apart from the active submaps (see active_submaps()), for checkpoints.
  LocalTrajectoryBuilderState2D ExportState() const;
  // Continues exactly where the exporting builder stopped; only on a builder that has not
  // seen any data yet. `active_submaps` are the restored active_submaps(), oldest first.
  void RestoreState(const LocalTrajectoryBuilderState2D& state,
                    std::vector<std::shared_ptr<Submap2D>> active_submaps);

 private:
  // Within kMaxPredictedJumpM of the last matched pose, and finite. Requires a pose.
  bool IsPlausiblePrediction(const common::Rigid2d& predicted) const;
  common::Rigid2d ScanMatch(const common::Rigid2d& predicted, const sensor::PointCloud2d& cloud,
                            double* score);
  // ScanMatch with initial_branch_and_bound_match.only_at_window_edge (see there).
  common::Rigid2d MatchWidenedAtWindowEdge(const common::Rigid2d& predicted,
                                           const sensor::PointCloud2d& cloud, double* score);

  LocalTrajectoryBuilderOptions2D options_;
  ActiveSubmaps2D active_submaps_;
  MotionFilter motion_filter_;
  InitialMatcher2D initial_matcher_;
  RealTimeCorrelativeScanMatcher2D real_time_matcher_;
  AdaptiveRotationPrior rotation_prior_;
  CeresScanMatcher2D ceres_matcher_;
  PoseExtrapolator2D extrapolator_;
  double last_scan_stamp_s_ = -1e300;
  // The last scan the motion filter let through (meaningful once stats_.inserted > 0).
  double last_insertion_stamp_s_ = 0.0;
  common::Rigid2d T_local_last_insertion_;
  Stats stats_;
};

// Everything LocalTrajectoryBuilder2D holds besides its options and active submaps.
struct LocalTrajectoryBuilderState2D {
  PoseExtrapolatorState2D extrapolator;
  double last_scan_stamp_s = -1e300;
  double last_insertion_stamp_s = 0.0;
  common::Rigid2d T_local_last_insertion;
  LocalTrajectoryBuilder2D::Stats stats;
  // AdaptiveRotationPrior's window: correction sizes, oldest first.
  std::vector<double> heading_corrections_rad;
};

}  // namespace mapping
}  // namespace fusemap

#endif  // FUSEMAP_MAPPING_LOCAL_TRAJECTORY_BUILDER_2D_H_
