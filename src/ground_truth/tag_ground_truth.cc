#include "fusemap/ground_truth/tag_ground_truth.h"

#include <cassert>
#include <utility>

namespace fusemap {
namespace ground_truth {

void TagGroundTruthOptions::Check(common::OptionChecker* check) const {
  check->Nested("detector", detector);
  check->Require(default_tag_size_m > 0.0, "default_tag_size_m", "must be > 0");
  check->Require(max_reprojection_rms_px > 0.0, "max_reprojection_rms_px", "must be > 0");
  check->Require(min_decision_margin >= 0.0, "min_decision_margin", "must be >= 0");
}

bool TagGroundTruthOptions::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

TagGroundTruthOptions ParseTagGroundTruthOptions(common::ConfigReader& reader) {
  TagGroundTruthOptions options;
  options.detector = ParseTagDetectorOptions(reader.Child("detector"));
  reader.Get("default_tag_size_m", &options.default_tag_size_m);
  reader.Get("max_reprojection_rms_px", &options.max_reprojection_rms_px);
  reader.Get("min_decision_margin", &options.min_decision_margin);
  if (reader.Has("T_base_camera")) {
    common::ConfigReader& child = reader.Child("T_base_camera");
    std::vector<double> t{0.0, 0.0, 0.0};
    std::vector<double> q{1.0, 0.0, 0.0, 0.0};
    child.Get("translation_m", &t);
    child.Get("rotation_wxyz", &q);
    if (t.size() != 3) child.AddError("translation_m", "needs 3 numbers [x, y, z]");
    if (q.size() != 4) child.AddError("rotation_wxyz", "needs 4 numbers [w, x, y, z]");
    const Eigen::Quaterniond rotation =
        q.size() == 4 ? Eigen::Quaterniond(q[0], q[1], q[2], q[3]) : Eigen::Quaterniond::Identity();
    if (q.size() == 4 && !(rotation.norm() > 1e-9)) {
      child.AddError("rotation_wxyz", "quaternion has zero norm");
    }
    if (t.size() == 3 && q.size() == 4 && rotation.norm() > 1e-9) {
      options.override_T_base_camera = true;
      options.T_base_camera = common::Rigid3d(Eigen::Vector3d(t[0], t[1], t[2]), rotation);
    }
  }
  reader.CheckOptions(options);
  return options;
}

TagGroundTruth::TagGroundTruth(const TagGroundTruthOptions& options, TagMap tag_map,
                               std::unique_ptr<TagDetector> detector)
    : options_(options), tag_map_(std::move(tag_map)), detector_(std::move(detector)) {
  assert(detector_ != nullptr);
}

FrameOutcome TagGroundTruth::AddFrame(const sensor::RgbdFrame& frame) {
  const sensor::PinholeIntrinsics& k = frame.color_intrinsics;
  assert(k.fx > 0.0 && k.fy > 0.0);
  return AddImage(frame.stamp_s, GreyFromRgb(k.width, k.height, frame.color_rgb), k,
                  options_.override_T_base_camera ? options_.T_base_camera : frame.T_base_color);
}

FrameOutcome TagGroundTruth::AddImage(double stamp_s, const GreyImage& image,
                                      const sensor::PinholeIntrinsics& intrinsics,
                                      const common::Rigid3d& T_base_camera) {
  std::vector<TagDetection> detections;
  for (const TagDetection& d : detector_->Detect(image)) {
    if (d.decision_margin >= options_.min_decision_margin) detections.push_back(d);
  }
  FrameOutcome outcome = FrameOutcome::kPose;
  CameraPoseEstimate estimate;
  if (detections.empty()) {
    outcome = FrameOutcome::kNoTag;
  } else if (!EstimateCameraPose(detections, tag_map_, intrinsics, &estimate)) {
    outcome = FrameOutcome::kOnlyUnknownTags;
  } else if (estimate.rms_reprojection_px > options_.max_reprojection_rms_px ||
             (!trajectory_.empty() && stamp_s <= trajectory_.back().stamp_s)) {
    outcome = FrameOutcome::kRejected;
  }
  for (int id : estimate.unknown_ids) ++unknown_tag_counts_[id];
  ++outcome_counts_[outcome];
  if (outcome != FrameOutcome::kPose) return outcome;

  const common::Rigid3d T_camera_base = T_base_camera.inverse();
  trajectory_.push_back({stamp_s, estimate.T_map_camera * T_camera_base});
  for (const TagDetection& d : detections) {
    const auto it = tag_map_.find(d.id);
    common::Rigid3d T_camera_tag;
    if (it == tag_map_.end() || !EstimateTagPose(d, intrinsics, it->second.size_m, &T_camera_tag)) {
      continue;
    }
    sightings_.push_back(
        {stamp_s, d.id, it->second.T_map_tag * T_camera_tag.inverse() * T_camera_base});
  }
  return outcome;
}

}  // namespace ground_truth
}  // namespace fusemap
