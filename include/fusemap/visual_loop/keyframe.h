#ifndef FUSEMAP_VISUAL_LOOP_KEYFRAME_H_
#define FUSEMAP_VISUAL_LOOP_KEYFRAME_H_

#include <cstddef>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "fusemap/sensor/rgbd_frame.h"
#include "fusemap/visual_loop/bow_vector.h"
#include "fusemap/visual_loop/orb_extractor.h"
#include "fusemap/visual_loop/vocabulary.h"

namespace fusemap {
namespace visual_loop {

// What the loop checker keeps of one camera image: keypoint positions, their ORB descriptors,
// the keypoints' 3D points in the camera's optical frame (z forward; NaN where depth had no
// value) and the image's bag of words. No pixels are kept. node and submap tie the keyframe to
// the pose graph (-1 when not known, as in the tools).
struct Keyframe {
  int id = -1;
  int node = -1;
  int submap = -1;
  double stamp_s = 0.0;
  int image_width = 0;
  int image_height = 0;
  sensor::PinholeIntrinsics intrinsics;
  std::vector<cv::Point2f> keypoints;
  cv::Mat descriptors;  // CV_8UC1, one 32-byte row per keypoint
  std::vector<Eigen::Vector3f> points_camera;  // empty without depth, else one per keypoint
  BowVector bow;
  // Per keypoint, its vocabulary node at KeyframeOptions::direct_index_level (empty without a
  // vocabulary): matching compares only keypoints under the same node.
  std::vector<uint32_t> vocabulary_nodes;

  bool has_depth() const { return !points_camera.empty(); }
  int num_points_with_depth() const;
  // Heap and object bytes held by this keyframe (what a map of them costs).
  size_t BytesUsed() const;
};

struct KeyframeOptions {
  double min_depth_m = 0.2;
  double max_depth_m = 6.0;  // structured-light depth beyond this is too noisy to anchor PnP
  // Level of the vocabulary tree whose nodes group keypoints for matching: 1 keeps the most
  // true matches (10 groups with k = 10), deeper levels match faster and lose more at borders.
  int direct_index_level = 1;
};

// Builds a keyframe from an image (grey or BGR) and, optionally, a depth image registered to it
// (CV_32FC1 in metres, 0 or NaN for no value; empty for none). vocabulary may be null (no BoW).
Keyframe MakeKeyframe(const cv::Mat& image, const cv::Mat& depth_m,
                      const sensor::PinholeIntrinsics& intrinsics, const OrbExtractor& extractor,
                      const Vocabulary* vocabulary, const KeyframeOptions& depth_options);

// A 16-bit depth image (value / scale = metres; 0 = no value) as CV_32FC1 metres.
cv::Mat DepthToMeters(const cv::Mat& depth_u16, double scale);

}  // namespace visual_loop
}  // namespace fusemap

#endif  // FUSEMAP_VISUAL_LOOP_KEYFRAME_H_
