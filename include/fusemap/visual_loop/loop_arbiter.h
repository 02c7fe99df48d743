#ifndef FUSEMAP_VISUAL_LOOP_LOOP_ARBITER_H_
#define FUSEMAP_VISUAL_LOOP_LOOP_ARBITER_H_

#include <optional>
#include <string>

#include <Eigen/Core>

#include "fusemap/common/rigid_transform.h"

namespace fusemap {
namespace visual_loop {

// One loop-closure measurement of a node in a submap (the pose graph's constraint), with what
// supports it: the laser matcher's score or the visual inliers.
struct LoopMeasurement2D {
  common::Rigid2d T_submap_node;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
  double laser_score = 0.0;  // laser only
  int visual_inliers = 0;    // visual only
  // Visual only, when a laser loop of the same place is arbitrated against it: how many of the
  // camera's descriptor matches the laser's relative pose explains (CountMatchesExplained);
  // -1 when not counted.
  int visual_matches_explained_by_laser = -1;
  // Laser only: the unit vector, in the node's frame, along which the match measured nothing
  // (a corridor of plain walls; pose_graph::Constraint2D::unmeasured_direction). There the
  // translation is the graph's estimate, not a measurement. Zero when it measures every way.
  Eigen::Vector2d unmeasured_direction = Eigen::Vector2d::Zero();
  // The turn, in rad per metre along unmeasured_direction, that goes with it (a curved wall).
  double unmeasured_turn_rad_per_m = 0.0;
};

// What the camera said about a place the laser closed on.
enum class VisualCheck {
  kNotChecked,    // no keyframes there, or the images had too little texture to judge
  kVerified,      // a verified visual loop (the measurement is given)
  kContradicted,  // both views were rich and should overlap, yet verification found no match
};

enum class LoopSource { kLaser, kVisual, kBoth };
enum class LoopDecision {
  kLaserConfirmed,   // both agree: the laser one is kept (more precise in 2D), both as evidence
  kVisualOverride,   // both exist and disagree: the visual one replaces the laser one
  kVisualForced,     // visual only: forced into the graph
  kLaserKept,        // laser only, the camera did not contradict it
  kLaserRejected,    // laser only and the camera positively contradicts it
  kVisualRejected,   // visual only, but asks a correction drift cannot explain: not forced
};
const char* ToString(LoopSource source);
const char* ToString(LoopDecision decision);

struct ArbitrationOptions {
  // Laser and visual agree when their relative poses differ by at most this much.
  double max_translation_disagreement_m = 0.3;
  double max_rotation_disagreement_rad = 0.1;
  // A visual loop without a laser loop is forced only if the correction it asks of the graph's
  // estimate is one that drift explains: at most max_forced_correction_m plus
  // forced_correction_per_m times the path travelled between the two views (and likewise in
  // rotation). Beyond that it is a second place that looks the same (one poster hung twice), or
  // the same wall seen from the other way. 10 % of the path is generous for wheel odometry
  // corrected by scan matching, and the laser searched only 4 m around its estimate.
  double max_forced_correction_m = 1.0;
  double forced_correction_per_m = 0.1;
  double max_forced_correction_rad = 0.35;
  double forced_correction_rad_per_m = 0.01;
  // Where they disagree, the visual loop replaces the laser one only if the laser's pose
  // explains at most this fraction as many of the camera's matches as the camera's own pose
  // does: otherwise the images do not tell the two apart (a wall seen far off at a narrow
  // angle fits a turn as well as a step sideways) and the laser loop is kept.
  double max_laser_explained_fraction = 0.5;
  bool IsValid(std::string* error) const;
};

// Where the pose graph puts the node in the submap now, and how far the robot travelled between
// the visual loop's two views (by the graph's poses): what a visual loop without a laser loop
// is checked against.
struct GraphEstimate2D {
  common::Rigid2d T_submap_node;
  double path_m = 0.0;
};

// Every decision as a record: which constraint enters the graph (none when rejected), why, and
// both measurements so that loops.tsv can show what was compared.
struct ArbitrationRecord {
  int node = -1;
  int submap = -1;
  LoopSource source = LoopSource::kLaser;
  LoopDecision decision = LoopDecision::kLaserKept;
  std::string reason;
  std::optional<LoopMeasurement2D> laser;
  std::optional<LoopMeasurement2D> visual;
  std::optional<LoopMeasurement2D> chosen;  // what the pose graph should add
  double translation_disagreement_m = 0.0;  // when both exist
  double rotation_disagreement_rad = 0.0;
};

// Whether a laser and a visual measurement of the same node in the same submap differ by more
// than max_translation_disagreement_m or max_rotation_disagreement_rad (where ArbitrateLoop
// weighs the one against the other).
bool LaserAndVisualDisagree(const LoopMeasurement2D& laser, const LoopMeasurement2D& visual,
                            const ArbitrationOptions& options);

// The arbitration of issue 17 for one node/submap pair. At least one of laser and a verified
// visual measurement must be given; visual_check describes the camera when visual is absent.
// `estimate`, when given, gates a visual loop without a laser loop (max_forced_correction_m).
ArbitrationRecord ArbitrateLoop(int node, int submap, const std::optional<LoopMeasurement2D>& laser,
                                const std::optional<LoopMeasurement2D>& visual,
                                VisualCheck visual_check, const ArbitrationOptions& options,
                                const std::optional<GraphEstimate2D>& estimate = std::nullopt);

}  // namespace visual_loop
}  // namespace fusemap

#endif  // FUSEMAP_VISUAL_LOOP_LOOP_ARBITER_H_
