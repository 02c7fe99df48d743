#ifndef FUSEMAP_IO_VISUAL_LOOP_CONFIG_H_
#define FUSEMAP_IO_VISUAL_LOOP_CONFIG_H_

#include <memory>
#include <string>

#include "fusemap/common/config_reader.h"
#include "fusemap/visual_loop/loop_arbiter.h"
#include "fusemap/visual_loop/visual_loop_checker.h"
#include "fusemap/visual_loop/vocabulary.h"

namespace fusemap {
namespace io {

// The `visual_loop:` section: the ORB visual loop checker beside the laser loop closure
// (session::VisualStage). Off by default.
// The camera's motion between consecutive keyframes as node links (pose_graph::NodeLink2D):
// each new keyframe is verified against the one before it, and the relative pose found joins
// the graph. In a corridor of plain walls local SLAM measures nothing along the corridor and
// the map takes the odometry's scale there; a camera that sees texture measures it.
struct MotionLinkOptions {
  bool enabled = true;
  // Residual = weights .* error, as loop constraints. translation_weight is that of a link the
  // verifier measured to 1 mm (standard error); one measured to s mm gets 1/s of it. Against
  // local SLAM's 1e5 a step, which along a direction its scan left unpinned counts
  // global_slam.linked_unmeasured_weight_fraction of that (so that the camera decides it).
  double translation_weight = 2e5;
  double rotation_weight = 1e4;
  // A link that differs from local SLAM's motion by more than this is a wrong match: refused.
  double max_disagreement_m = 0.3;
  double max_disagreement_rad = 0.1;
};

struct VisualLoopConfig {
  bool enabled = false;
  // As written: absolute, or relative to the source tree (FUSEMAP_SOURCE_DIR).
  std::string vocabulary = "data/vocabulary/orb_k10_l4.bin";
  // Loaded when enabled (ParseVisualLoopConfig); shared by copies of the config.
  std::shared_ptr<const visual_loop::Vocabulary> loaded_vocabulary;
  visual_loop::VisualLoopCheckerOptions checker;
  visual_loop::ArbitrationOptions arbitration;
  // Weights of the loop constraints the checker adds or substitutes: by default the laser
  // loop weights of config/sim.yaml (Cartographer's), the profile the checker was tuned in;
  // the default profile's laser loops weigh 100x that.
  double translation_weight = 1.1e4;
  double rotation_weight = 1e5;
  // A laser loop of node N is checked against the keyframe nearest N only if that keyframe's
  // node is at most this many nodes away; a visual loop and a laser loop are one pair when
  // their nodes are this close (and the submap is the same).
  int max_node_gap = 5;
  // A laser loop is checked against the submap's keyframe nearest where it puts the node, and
  // only if that keyframe stands within this distance and turn of it (farther views are not a
  // check of that place; the loop is then kept unchecked).
  double max_check_distance_m = 1.5;
  double max_check_yaw_rad = 0.8;
  // How many of those keyframes (nearest first) are tried; a laser loop is rejected only if
  // every one tried contradicts it.
  int max_check_views = 3;
  // Frames waiting for a laser pose newer than themselves; beyond this the oldest is dropped.
  int max_pending_frames = 16;
  // fusemapd: frames queued for the checker's own thread; when full the oldest is dropped.
  int max_queue_frames = 8;
  MotionLinkOptions motion_links;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  bool IsValid(std::string* error) const;
};

// The vocabulary path as given, or resolved against the source tree if relative.
std::string ResolveVocabularyPath(const std::string& path);
// Loads config->vocabulary into config->loaded_vocabulary (for a config enabled after parsing,
// e.g. by a command-line flag); false with the reason otherwise.
bool LoadVisualLoopVocabulary(VisualLoopConfig* config, std::string* error);

// Keys: enabled, vocabulary, translation_weight, rotation_weight, max_node_gap,
// max_check_distance_m, max_check_yaw_rad, max_check_views, max_pending_frames, max_queue_frames, keyframes (min_translation_m, min_rotation_rad,
// max_interval_s, min_interval_s, max_features, min_depth_m, max_depth_m), recognition
// (num_recent_excluded, min_normalized_score, temporal_consistency, island_gap), verification
// (min_inliers, pnp_threshold_px, max_mean_reprojection_px, min_occupied_cells), planar
// (max_roll_pitch_rad, max_height_m), contradiction (min_points, max_overlap_distance_m,
// max_overlap_yaw_rad, max_inliers), arbitration (max_translation_disagreement_m,
// max_rotation_disagreement_rad, max_forced_correction_m, forced_correction_per_m,
// max_forced_correction_rad, forced_correction_rad_per_m). With enabled, a vocabulary that
// cannot be loaded is an error against the `vocabulary` key.
VisualLoopConfig ParseVisualLoopConfig(common::ConfigReader& reader);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_VISUAL_LOOP_CONFIG_H_
