#include "fusemap/visual_loop/loop_arbiter.h"

#include <cassert>
#include <cmath>
#include <cstdio>

namespace fusemap {
namespace visual_loop {

bool ArbitrationOptions::IsValid(std::string* error) const {
  if (!(max_translation_disagreement_m > 0.0) || !(max_rotation_disagreement_rad > 0.0)) {
    *error = "arbitration: disagreement thresholds must be positive";
    return false;
  }
  if (!(max_laser_explained_fraction >= 0.0 && max_laser_explained_fraction <= 1.0)) {
    *error = "arbitration: max_laser_explained_fraction must be in [0, 1]";
    return false;
  }
  if (!(max_forced_correction_m > 0.0) || !(forced_correction_per_m >= 0.0) ||
      !(max_forced_correction_rad > 0.0) || !(forced_correction_rad_per_m >= 0.0)) {
    *error = "arbitration: forced correction bounds must be positive (their per-metre rates >= 0)";
    return false;
  }
  return true;
}

const char* ToString(LoopSource source) {
  switch (source) {
    case LoopSource::kLaser:
      return "laser";
    case LoopSource::kVisual:
      return "visual";
    case LoopSource::kBoth:
      return "both";
  }
  return "?";
}

const char* ToString(LoopDecision decision) {
  switch (decision) {
    case LoopDecision::kLaserConfirmed:
      return "laser_confirmed";
    case LoopDecision::kVisualOverride:
      return "visual_override";
    case LoopDecision::kVisualForced:
      return "visual_forced";
    case LoopDecision::kLaserKept:
      return "laser_kept";
    case LoopDecision::kLaserRejected:
      return "laser_rejected";
    case LoopDecision::kVisualRejected:
      return "visual_rejected";
  }
  return "?";
}

bool LaserAndVisualDisagree(const LoopMeasurement2D& laser, const LoopMeasurement2D& visual,
                            const ArbitrationOptions& options) {
  const common::Rigid2d difference = laser.T_submap_node.inverse() * visual.T_submap_node;
  return difference.translation().norm() > options.max_translation_disagreement_m ||
         std::abs(difference.angle_rad()) > options.max_rotation_disagreement_rad;
}

ArbitrationRecord ArbitrateLoop(int node, int submap, const std::optional<LoopMeasurement2D>& laser,
                                const std::optional<LoopMeasurement2D>& visual,
                                VisualCheck visual_check, const ArbitrationOptions& options,
                                const std::optional<GraphEstimate2D>& estimate) {
  assert(laser || visual);
  ArbitrationRecord record;
  record.node = node;
  record.submap = submap;
  record.laser = laser;
  record.visual = visual;
  if (laser && visual) {
    record.source = LoopSource::kBoth;
    const common::Rigid2d difference = laser->T_submap_node.inverse() * visual->T_submap_node;
    record.translation_disagreement_m = difference.translation().norm();
    record.rotation_disagreement_rad = std::abs(difference.angle_rad());
    char numbers[96];
    std::snprintf(numbers, sizeof(numbers), "differ by %.3f m, %.2f deg",
                  record.translation_disagreement_m, record.rotation_disagreement_rad * 180.0 / M_PI);
    const bool agree = !LaserAndVisualDisagree(*laser, *visual, options);
    const bool laser_explains_as_well =
        visual->visual_matches_explained_by_laser >= 0 &&
        visual->visual_matches_explained_by_laser >
            options.max_laser_explained_fraction * visual->visual_inliers;
    if (agree) {
      record.decision = LoopDecision::kLaserConfirmed;
      record.chosen = laser;
      record.reason = std::string("laser and visual agree (") + numbers + "): laser kept";
    } else if (laser_explains_as_well) {
      record.decision = LoopDecision::kLaserKept;
      record.chosen = laser;
      record.reason = std::string("laser and visual disagree (") + numbers +
                      "), but the laser's pose explains " +
                      std::to_string(visual->visual_matches_explained_by_laser) +
                      " of the camera's matches against its own " +
                      std::to_string(visual->visual_inliers) + ": laser kept";
    } else {
      record.decision = LoopDecision::kVisualOverride;
      record.chosen = visual;
      record.reason = std::string("laser and visual disagree (") + numbers + "): visual replaces laser";
    }
    return record;
  }
  if (visual) {
    record.source = LoopSource::kVisual;
    if (estimate) {
      const common::Rigid2d correction = estimate->T_submap_node.inverse() * visual->T_submap_node;
      const double bound_m =
          options.max_forced_correction_m + options.forced_correction_per_m * estimate->path_m;
      const double bound_rad = options.max_forced_correction_rad +
                               options.forced_correction_rad_per_m * estimate->path_m;
      const double correction_m = correction.translation().norm();
      const double correction_rad = std::abs(correction.angle_rad());
      if (correction_m > bound_m || correction_rad > bound_rad) {
        char numbers[192];
        std::snprintf(numbers, sizeof(numbers),
                      "asks a correction of %.2f m, %.1f deg; drift over %.1f m of path explains "
                      "%.2f m, %.1f deg",
                      correction_m, correction_rad * 180.0 / M_PI, estimate->path_m, bound_m,
                      bound_rad * 180.0 / M_PI);
        record.decision = LoopDecision::kVisualRejected;
        record.reason = std::string("visual loop without a laser loop ") + numbers + ": rejected";
        return record;
      }
    }
    record.decision = LoopDecision::kVisualForced;
    record.chosen = visual;
    record.reason = "visual loop without a laser loop: forced";
    return record;
  }
  record.source = LoopSource::kLaser;
  if (visual_check == VisualCheck::kContradicted) {
    record.decision = LoopDecision::kLaserRejected;
    record.reason = "the camera saw the same place and found no match: laser loop rejected";
    return record;
  }
  record.decision = LoopDecision::kLaserKept;
  record.chosen = laser;
  record.reason = visual_check == VisualCheck::kNotChecked
                      ? "laser loop, no visual check possible: kept"
                      : "laser loop, visual check consistent: kept";
  return record;
}

}  // namespace visual_loop
}  // namespace fusemap
