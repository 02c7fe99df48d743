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
};
const char* ToString(LoopSource source);
const char* ToString(LoopDecision decision);

struct ArbitrationOptions {
  // Laser and visual agree when their relative poses differ by at most this much.
  double max_translation_disagreement_m = 0.3;
  double max_rotation_disagreement_rad = 0.1;
  bool IsValid(std::string* error) const;
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

// The arbitration of issue 17 for one node/submap pair. At least one of laser and a verified
// visual measurement must be given; visual_check describes the camera when visual is absent.
ArbitrationRecord ArbitrateLoop(int node, int submap, const std::optional<LoopMeasurement2D>& laser,
                                const std::optional<LoopMeasurement2D>& visual,
                                VisualCheck visual_check, const ArbitrationOptions& options);

}  // namespace visual_loop
}  // namespace fusemap

#endif  // FUSEMAP_VISUAL_LOOP_LOOP_ARBITER_H_
