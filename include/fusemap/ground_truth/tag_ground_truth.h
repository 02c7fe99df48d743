#ifndef FUSEMAP_GROUND_TRUTH_TAG_GROUND_TRUTH_H_
#define FUSEMAP_GROUND_TRUTH_TAG_GROUND_TRUTH_H_

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "fusemap/common/config_reader.h"
#include "fusemap/common/rigid_transform.h"
#include "fusemap/eval/trajectory.h"
#include "fusemap/ground_truth/tag_detector.h"
#include "fusemap/ground_truth/tag_map.h"
#include "fusemap/ground_truth/tag_pose.h"
#include "fusemap/sensor/rgbd_frame.h"

namespace fusemap {
namespace ground_truth {

struct TagGroundTruthOptions {
  TagDetectorOptions detector;
  // Size for tags the tag map lists without one (io/tag_map.h fills it in when reading).
  double default_tag_size_m = 0.16;
  // When set, replaces each frame's T_base_color (a mis-calibrated driver, or an older log).
  bool override_T_base_camera = false;
  common::Rigid3d T_base_camera;
  // Frames whose joint solution reprojects worse than this are rejected as outliers.
  double max_reprojection_rms_px = 2.0;
  // Detections with a weaker decode (AprilTag decision margin) are ignored.
  double min_decision_margin = 20.0;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

// Keys: detector {family, quad_decimate, ...}, default_tag_size_m,
// T_base_camera {translation_m: [x, y, z], rotation_wxyz: [w, x, y, z]} (present = override),
// max_reprojection_rms_px, min_decision_margin.
TagGroundTruthOptions ParseTagGroundTruthOptions(common::ConfigReader& reader);

// The robot pose seen through one tag alone: for per-tag residuals.
struct TagSighting {
  double stamp_s = 0.0;
  int tag_id = -1;
  common::Rigid3d T_map_base;
};

enum class FrameOutcome { kPose, kNoTag, kOnlyUnknownTags, kRejected };

// Turns camera frames into ground-truth robot poses:
// T_map_base = T_map_tag * T_tag_camera * T_camera_base, with T_map_camera solved jointly from
// every known tag in the frame (tag_pose.h). Unknown tag ids are counted, never fatal.
class TagGroundTruth {
 public:
  TagGroundTruth(const TagGroundTruthOptions& options, TagMap tag_map,
                 std::unique_ptr<TagDetector> detector);

  // Precondition: frame.color_intrinsics has positive focal lengths and the colour buffer
  // matches its size (check at the edge).
  FrameOutcome AddFrame(const sensor::RgbdFrame& frame);
  // The same, for an image already in grey with its intrinsics and extrinsic.
  FrameOutcome AddImage(double stamp_s, const GreyImage& image,
                        const sensor::PinholeIntrinsics& intrinsics,
                        const common::Rigid3d& T_base_camera);

  const eval::Trajectory& trajectory() const { return trajectory_; }
  const std::vector<TagSighting>& sightings() const { return sightings_; }
  // Detections per unknown id.
  const std::map<int, int>& unknown_tag_counts() const { return unknown_tag_counts_; }
  const std::map<FrameOutcome, int>& outcome_counts() const { return outcome_counts_; }

 private:
  TagGroundTruthOptions options_;
  TagMap tag_map_;
  std::unique_ptr<TagDetector> detector_;
  eval::Trajectory trajectory_;
  std::vector<TagSighting> sightings_;
  std::map<int, int> unknown_tag_counts_;
  std::map<FrameOutcome, int> outcome_counts_;
};

}  // namespace ground_truth
}  // namespace fusemap

#endif  // FUSEMAP_GROUND_TRUTH_TAG_GROUND_TRUTH_H_
