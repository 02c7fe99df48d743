#include "fusemap/visual_loop/keyframe.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace fusemap {
namespace visual_loop {

int Keyframe::num_points_with_depth() const {
  int count = 0;
  for (const Eigen::Vector3f& p : points_camera) count += std::isfinite(p.z()) ? 1 : 0;
  return count;
}

size_t Keyframe::BytesUsed() const {
  return sizeof(Keyframe) + keypoints.capacity() * sizeof(cv::Point2f) +
         descriptors.total() * descriptors.elemSize() +
         points_camera.capacity() * sizeof(Eigen::Vector3f) +
         bow.capacity() * sizeof(BowVector::value_type) +
         vocabulary_nodes.capacity() * sizeof(uint32_t);
}

Keyframe MakeKeyframe(const cv::Mat& image, const cv::Mat& depth_m,
                      const sensor::PinholeIntrinsics& intrinsics, const OrbExtractor& extractor,
                      const Vocabulary* vocabulary, const KeyframeOptions& options) {
  assert(depth_m.empty() || (depth_m.type() == CV_32FC1 && depth_m.size() == image.size()));
  const cv::Mat gray = ToGray(image);
  OrbFeatures features = extractor.Extract(gray);
  Keyframe keyframe;
  keyframe.image_width = gray.cols;
  keyframe.image_height = gray.rows;
  keyframe.intrinsics = intrinsics;
  keyframe.keypoints.reserve(features.keypoints.size());
  for (const cv::KeyPoint& k : features.keypoints) keyframe.keypoints.push_back(k.pt);
  keyframe.descriptors = features.descriptors;
  if (!depth_m.empty()) {
    assert(intrinsics.fx > 0.0 && intrinsics.fy > 0.0);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    keyframe.points_camera.reserve(keyframe.keypoints.size());
    for (const cv::Point2f& pt : keyframe.keypoints) {
      const int u = std::min(std::max(static_cast<int>(std::lround(pt.x)), 0), depth_m.cols - 1);
      const int v = std::min(std::max(static_cast<int>(std::lround(pt.y)), 0), depth_m.rows - 1);
      const float z = depth_m.at<float>(v, u);
      if (!(z >= options.min_depth_m && z <= options.max_depth_m)) {
        keyframe.points_camera.emplace_back(nan, nan, nan);
        continue;
      }
      keyframe.points_camera.emplace_back(static_cast<float>((pt.x - intrinsics.cx) * z / intrinsics.fx),
                                          static_cast<float>((pt.y - intrinsics.cy) * z / intrinsics.fy),
                                          z);
    }
  }
  if (vocabulary != nullptr) {
    keyframe.bow = vocabulary->Transform(keyframe.descriptors, options.direct_index_level,
                                         &keyframe.vocabulary_nodes);
  }
  return keyframe;
}

cv::Mat DepthToMeters(const cv::Mat& depth_u16, double scale) {
  assert(depth_u16.type() == CV_16UC1 && scale > 0.0);
  cv::Mat meters;
  depth_u16.convertTo(meters, CV_32FC1, 1.0 / scale);
  return meters;
}

}  // namespace visual_loop
}  // namespace fusemap
