#include "fusemap/io/visual_loop_config.h"

#include <filesystem>

namespace fusemap {
namespace io {
namespace {

// Each subsection's rules, against its own keys (ConfigReader::CheckOptions takes a struct with
// Check()); the library's IsValid() stays the final word for options built in C++.
struct KeyframeRules {
  const visual_loop::VisualLoopCheckerOptions& o;
  void Check(common::OptionChecker* c) const {
    c->Require(o.selector.min_translation_m > 0.0, "min_translation_m", "must be > 0");
    c->Require(o.selector.min_rotation_rad > 0.0, "min_rotation_rad", "must be > 0");
    c->Require(o.selector.max_interval_s > o.selector.min_interval_s, "max_interval_s",
               "must be > min_interval_s");
    c->Require(o.selector.min_interval_s >= 0.0, "min_interval_s", "must be >= 0");
    c->Require(o.orb.max_features >= 50, "max_features", "must be >= 50");
    c->Require(o.keyframe.min_depth_m >= 0.0, "min_depth_m", "must be >= 0");
    c->Require(o.keyframe.max_depth_m > o.keyframe.min_depth_m, "max_depth_m",
               "must be > min_depth_m");
  }
};

struct RecognitionRules {
  const visual_loop::PlaceRecognitionOptions& o;
  void Check(common::OptionChecker* c) const {
    c->Require(o.num_recent_excluded >= 0, "num_recent_excluded", "must be >= 0");
    c->Require(o.min_normalized_score > 0.0, "min_normalized_score", "must be > 0");
    c->Require(o.temporal_consistency >= 0, "temporal_consistency", "must be >= 0");
    c->Require(o.island_gap >= 0, "island_gap", "must be >= 0");
  }
};

struct VerificationRules {
  const visual_loop::VerificationOptions& o;
  void Check(common::OptionChecker* c) const {
    c->Require(o.min_inliers >= 6, "min_inliers", "must be >= 6");
    c->Require(o.pnp_threshold_px > 0.0, "pnp_threshold_px", "must be > 0");
    c->Require(o.max_mean_reprojection_px > 0.0, "max_mean_reprojection_px", "must be > 0");
    c->Require(o.min_occupied_cells >= 1 && o.min_occupied_cells <= o.grid_cols * o.grid_rows,
               "min_occupied_cells",
               "must be in [1, " + std::to_string(o.grid_cols * o.grid_rows) + "]");
  }
};

struct PlanarRules {
  const visual_loop::PlanarConstraintOptions& o;
  void Check(common::OptionChecker* c) const {
    c->Require(o.max_roll_pitch_rad > 0.0, "max_roll_pitch_rad", "must be > 0");
    c->Require(o.max_height_m > 0.0, "max_height_m", "must be > 0");
  }
};

struct ContradictionRules {
  const visual_loop::VisualLoopCheckerOptions& o;
  void Check(common::OptionChecker* c) const {
    c->Require(o.min_points_to_contradict >= 1, "min_points", "must be >= 1");
    c->Require(o.max_overlap_distance_m > 0.0, "max_overlap_distance_m", "must be > 0");
    c->Require(o.max_overlap_yaw_rad > 0.0, "max_overlap_yaw_rad", "must be > 0");
    c->Require(o.max_contradiction_inliers >= 0, "max_inliers", "must be >= 0");
  }
};

struct MotionLinkRules {
  const MotionLinkOptions& o;
  void Check(common::OptionChecker* c) const {
    c->Require(o.translation_weight > 0.0, "translation_weight", "must be > 0");
    c->Require(o.rotation_weight > 0.0, "rotation_weight", "must be > 0");
    c->Require(o.max_disagreement_m > 0.0, "max_disagreement_m", "must be > 0");
    c->Require(o.max_disagreement_rad > 0.0, "max_disagreement_rad", "must be > 0");
  }
};

struct ArbitrationRules {
  const visual_loop::ArbitrationOptions& o;
  void Check(common::OptionChecker* c) const {
    c->Require(o.max_translation_disagreement_m > 0.0, "max_translation_disagreement_m",
               "must be > 0");
    c->Require(o.max_rotation_disagreement_rad > 0.0, "max_rotation_disagreement_rad",
               "must be > 0");
    c->Require(o.max_forced_correction_m > 0.0, "max_forced_correction_m", "must be > 0");
    c->Require(o.forced_correction_per_m >= 0.0, "forced_correction_per_m", "must be >= 0");
    c->Require(o.max_forced_correction_rad > 0.0, "max_forced_correction_rad", "must be > 0");
    c->Require(o.forced_correction_rad_per_m >= 0.0, "forced_correction_rad_per_m",
               "must be >= 0");
    c->Require(o.max_laser_explained_fraction >= 0.0 && o.max_laser_explained_fraction <= 1.0,
               "max_laser_explained_fraction", "must be in [0, 1]");
  }
};

}  // namespace

void VisualLoopConfig::Check(common::OptionChecker* check) const {
  check->Require(!vocabulary.empty(), "vocabulary", "must name a file");
  check->Require(translation_weight > 0.0, "translation_weight", "must be > 0");
  check->Require(rotation_weight > 0.0, "rotation_weight", "must be > 0");
  check->Require(max_node_gap >= 0, "max_node_gap", "must be >= 0");
  check->Require(max_check_distance_m > 0.0, "max_check_distance_m", "must be > 0");
  check->Require(max_check_yaw_rad > 0.0, "max_check_yaw_rad", "must be > 0");
  check->Require(max_check_views >= 1, "max_check_views", "must be >= 1");
  check->Require(max_pending_frames >= 1, "max_pending_frames", "must be >= 1");
  check->Require(max_queue_frames >= 1, "max_queue_frames", "must be >= 1");
  check->Nested("keyframes", KeyframeRules{checker});
  check->Nested("recognition", RecognitionRules{checker.detector.recognition});
  check->Nested("verification", VerificationRules{checker.detector.verification});
  check->Nested("planar", PlanarRules{checker.planar});
  check->Nested("contradiction", ContradictionRules{checker});
  check->Nested("arbitration", ArbitrationRules{arbitration});
  check->Nested("motion_links", MotionLinkRules{motion_links});
}

bool VisualLoopConfig::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error) && checker.IsValid(error) &&
         arbitration.IsValid(error);
}

std::string ResolveVocabularyPath(const std::string& path) {
  const std::filesystem::path given(path);
  if (given.is_absolute()) return path;
  return (std::filesystem::path(FUSEMAP_SOURCE_DIR) / given).lexically_normal().string();
}

bool LoadVisualLoopVocabulary(VisualLoopConfig* config, std::string* error) {
  auto vocabulary = visual_loop::Vocabulary::Load(ResolveVocabularyPath(config->vocabulary), error);
  if (!vocabulary) return false;
  config->loaded_vocabulary =
      std::make_shared<const visual_loop::Vocabulary>(std::move(*vocabulary));
  return true;
}

VisualLoopConfig ParseVisualLoopConfig(common::ConfigReader& reader) {
  VisualLoopConfig config;
  visual_loop::VisualLoopCheckerOptions& checker = config.checker;
  reader.Get("enabled", &config.enabled);
  reader.Get("vocabulary", &config.vocabulary);
  reader.Get("translation_weight", &config.translation_weight);
  reader.Get("rotation_weight", &config.rotation_weight);
  reader.Get("max_node_gap", &config.max_node_gap);
  reader.Get("max_check_distance_m", &config.max_check_distance_m);
  reader.Get("max_check_yaw_rad", &config.max_check_yaw_rad);
  reader.Get("max_check_views", &config.max_check_views);
  reader.Get("max_pending_frames", &config.max_pending_frames);
  reader.Get("max_queue_frames", &config.max_queue_frames);

  common::ConfigReader& keyframes = reader.Child("keyframes");
  keyframes.Get("min_translation_m", &checker.selector.min_translation_m);
  keyframes.Get("min_rotation_rad", &checker.selector.min_rotation_rad);
  keyframes.Get("max_interval_s", &checker.selector.max_interval_s);
  keyframes.Get("min_interval_s", &checker.selector.min_interval_s);
  keyframes.Get("max_features", &checker.orb.max_features);
  keyframes.Get("min_depth_m", &checker.keyframe.min_depth_m);
  keyframes.Get("max_depth_m", &checker.keyframe.max_depth_m);
  keyframes.CheckOptions(KeyframeRules{checker});

  visual_loop::PlaceRecognitionOptions& recognition = checker.detector.recognition;
  common::ConfigReader& recognition_reader = reader.Child("recognition");
  recognition_reader.Get("num_recent_excluded", &recognition.num_recent_excluded);
  recognition_reader.Get("min_normalized_score", &recognition.min_normalized_score);
  recognition_reader.Get("temporal_consistency", &recognition.temporal_consistency);
  recognition_reader.Get("island_gap", &recognition.island_gap);
  recognition_reader.CheckOptions(RecognitionRules{recognition});

  visual_loop::VerificationOptions& verification = checker.detector.verification;
  common::ConfigReader& verification_reader = reader.Child("verification");
  verification_reader.Get("min_inliers", &verification.min_inliers);
  verification_reader.Get("pnp_threshold_px", &verification.pnp_threshold_px);
  verification_reader.Get("max_mean_reprojection_px", &verification.max_mean_reprojection_px);
  verification_reader.Get("min_occupied_cells", &verification.min_occupied_cells);
  verification_reader.CheckOptions(VerificationRules{verification});

  common::ConfigReader& planar = reader.Child("planar");
  planar.Get("max_roll_pitch_rad", &checker.planar.max_roll_pitch_rad);
  planar.Get("max_height_m", &checker.planar.max_height_m);
  planar.CheckOptions(PlanarRules{checker.planar});

  common::ConfigReader& contradiction = reader.Child("contradiction");
  contradiction.Get("min_points", &checker.min_points_to_contradict);
  contradiction.Get("max_overlap_distance_m", &checker.max_overlap_distance_m);
  contradiction.Get("max_overlap_yaw_rad", &checker.max_overlap_yaw_rad);
  contradiction.Get("max_inliers", &checker.max_contradiction_inliers);
  contradiction.CheckOptions(ContradictionRules{checker});

  common::ConfigReader& arbitration = reader.Child("arbitration");
  arbitration.Get("max_translation_disagreement_m",
                  &config.arbitration.max_translation_disagreement_m);
  arbitration.Get("max_rotation_disagreement_rad",
                  &config.arbitration.max_rotation_disagreement_rad);
  arbitration.Get("max_forced_correction_m", &config.arbitration.max_forced_correction_m);
  arbitration.Get("forced_correction_per_m", &config.arbitration.forced_correction_per_m);
  arbitration.Get("max_forced_correction_rad", &config.arbitration.max_forced_correction_rad);
  arbitration.Get("forced_correction_rad_per_m",
                  &config.arbitration.forced_correction_rad_per_m);
  arbitration.Get("max_laser_explained_fraction", &config.arbitration.max_laser_explained_fraction);
  arbitration.CheckOptions(ArbitrationRules{config.arbitration});

  common::ConfigReader& motion_links = reader.Child("motion_links");
  motion_links.Get("enabled", &config.motion_links.enabled);
  motion_links.Get("translation_weight", &config.motion_links.translation_weight);
  motion_links.Get("rotation_weight", &config.motion_links.rotation_weight);
  motion_links.Get("max_disagreement_m", &config.motion_links.max_disagreement_m);
  motion_links.Get("max_disagreement_rad", &config.motion_links.max_disagreement_rad);
  motion_links.Get("refine_on_pixels", &checker.refine_latest_on_pixels);
  motion_links.CheckOptions(MotionLinkRules{config.motion_links});

  reader.CheckOptions(config);
  std::string error;
  if (config.enabled && config.IsValid(&error) && !LoadVisualLoopVocabulary(&config, &error)) {
    reader.AddError("vocabulary", error);
  }
  return config;
}

}  // namespace io
}  // namespace fusemap
