#include "fusemap/visual_loop/orb_extractor.h"

#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "fusemap/visual_loop/keyframe.h"
#include "visual_loop/synthetic_views.h"

namespace fusemap {
namespace visual_loop {
namespace {

TEST(OrbExtractorTest, KeepsTheBudgetSpreadOverTheGrid) {
  const cv::Mat image = testing::RandomTexture(640, 480, 3);
  OrbOptions options;
  const OrbFeatures features = OrbExtractor(options).Extract(image);
  EXPECT_GT(features.keypoints.size(), 900u);
  EXPECT_LE(features.keypoints.size(), 1000u);
  EXPECT_EQ(features.descriptors.rows, static_cast<int>(features.keypoints.size()));
  EXPECT_EQ(features.descriptors.cols, 32);
  std::vector<int> per_cell(options.grid_cols * options.grid_rows, 0);
  for (const cv::KeyPoint& k : features.keypoints) {
    ++per_cell[static_cast<int>(k.pt.y * options.grid_rows / 480) * options.grid_cols +
               static_cast<int>(k.pt.x * options.grid_cols / 640)];
  }
  // Inner cells all hold corners; the outer ones fewer (no descriptor fits at the border).
  int occupied = 0;
  for (int row = 0; row < options.grid_rows; ++row) {
    for (int col = 0; col < options.grid_cols; ++col) {
      const int count = per_cell[row * options.grid_cols + col];
      occupied += count > 0 ? 1 : 0;
      const bool inner = row > 0 && col > 0 && row + 1 < options.grid_rows && col + 1 < options.grid_cols;
      if (inner) {
        EXPECT_GE(count, 10) << row << "," << col;
      }
    }
  }
  EXPECT_GE(occupied, 44);
}

TEST(OrbExtractorTest, TexturelessImageGivesNoFeatures) {
  const cv::Mat blank(480, 640, CV_8UC1, cv::Scalar(90));
  const OrbFeatures features = OrbExtractor(OrbOptions{}).Extract(blank);
  EXPECT_TRUE(features.keypoints.empty());
  EXPECT_EQ(features.descriptors.cols, 32);
}

TEST(OrbExtractorTest, CoarseLevelKeypointsSitOnTheirCornersNotUpAndLeftOfThem) {
  // A corner found in an image and in the image turned half round is the same corner: mapped
  // back, the two positions agree on average unless the extractor shifts every keypoint of a
  // level one way (OpenCV's own coordinates put level 2's ~0.5 px up-left, level 6's ~1.5 px).
  const cv::Mat image = testing::RandomTexture(640, 480, 5);
  cv::Mat turned;
  cv::rotate(image, turned, cv::ROTATE_180);
  const OrbOptions options;
  const OrbExtractor extractor(options);
  const OrbFeatures found = extractor.Extract(image);
  const OrbFeatures found_turned = extractor.Extract(turned);
  int levels_checked = 0;
  for (int level = 2; level < options.num_levels; ++level) {
    const double scale = std::pow(options.scale_factor, level);
    Eigen::Vector2d offset_sum = Eigen::Vector2d::Zero();
    int pairs = 0;
    for (const cv::KeyPoint& k : found.keypoints) {
      if (k.octave != level) continue;
      const cv::KeyPoint* nearest = nullptr;
      double nearest_distance = 2.0 * scale;
      Eigen::Vector2d nearest_offset;
      for (const cv::KeyPoint& t : found_turned.keypoints) {
        if (t.octave != level) continue;
        const Eigen::Vector2d offset(k.pt.x - (image.cols - 1 - t.pt.x),
                                     k.pt.y - (image.rows - 1 - t.pt.y));
        if (offset.norm() < nearest_distance) {
          nearest = &t;
          nearest_distance = offset.norm();
          nearest_offset = offset;
        }
      }
      if (nearest == nullptr) continue;
      offset_sum += nearest_offset;
      ++pairs;
    }
    if (pairs < 20) continue;
    ++levels_checked;
    // Twice the shift of one keypoint (each of the pair is shifted, in opposite directions).
    const Eigen::Vector2d mean_offset = offset_sum / pairs;
    EXPECT_LT(std::abs(mean_offset.x()), 0.2) << "level " << level << ", " << pairs << " pairs";
    EXPECT_LT(std::abs(mean_offset.y()), 0.2) << "level " << level << ", " << pairs << " pairs";
  }
  EXPECT_GE(levels_checked, 4);
}

TEST(OrbExtractorTest, KeyframeBackProjectsDepthAndStaysCompact) {
  const sensor::PinholeIntrinsics in = testing::TestIntrinsics();
  const cv::Mat image = testing::RandomTexture(640, 480, 4);
  cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(2.0f));
  depth(cv::Rect(0, 0, 320, 480)).setTo(0.0f);  // no depth on the left half
  const Keyframe keyframe = MakeKeyframe(image, depth, in, OrbExtractor(OrbOptions{}), nullptr, KeyframeOptions{});
  ASSERT_EQ(keyframe.points_camera.size(), keyframe.keypoints.size());
  int with_depth = 0;
  for (size_t i = 0; i < keyframe.keypoints.size(); ++i) {
    const Eigen::Vector3f& p = keyframe.points_camera[i];
    if (!std::isfinite(p.z())) {
      EXPECT_LT(keyframe.keypoints[i].x, 320.5f);
      continue;
    }
    ++with_depth;
    EXPECT_FLOAT_EQ(p.z(), 2.0f);
    EXPECT_NEAR(p.x() * in.fx / p.z() + in.cx, keyframe.keypoints[i].x, 1e-3);
    EXPECT_NEAR(p.y() * in.fy / p.z() + in.cy, keyframe.keypoints[i].y, 1e-3);
  }
  EXPECT_EQ(with_depth, keyframe.num_points_with_depth());
  EXPECT_GT(with_depth, 300);
  // 1000 keypoints: 8 + 32 + 12 bytes each, plus the object.
  EXPECT_LT(keyframe.BytesUsed(), 60000u);
}

}  // namespace
}  // namespace visual_loop
}  // namespace fusemap
