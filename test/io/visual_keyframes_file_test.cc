#include "fusemap/io/visual_keyframes_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace fusemap {
namespace io {
namespace {

VisualKeyframesState TwoKeyframes() {
  VisualKeyframesState state;
  state.next_keyframe_id = 9;
  for (int id : {3, 7}) {
    VisualKeyframesState::Entry entry;
    visual_loop::Keyframe& k = entry.saved.keyframe;
    k.id = id;
    k.node = 10 * id;
    k.submap = id / 2;
    k.stamp_s = 1.5 * id;
    k.image_width = k.intrinsics.width = 640;
    k.image_height = k.intrinsics.height = 480;
    k.intrinsics.fx = k.intrinsics.fy = 525.0;
    k.intrinsics.cx = 319.5;
    k.intrinsics.cy = 239.5;
    k.descriptors = cv::Mat(3, 32, CV_8UC1);
    for (int i = 0; i < 3; ++i) {
      k.keypoints.emplace_back(10.5f * i, 20.25f + i);
      for (int b = 0; b < 32; ++b) k.descriptors.at<uint8_t>(i, b) = static_cast<uint8_t>(id * i + b);
      k.vocabulary_nodes.push_back(100 + i);
      // A keypoint without depth keeps NaN.
      const float nan = std::numeric_limits<float>::quiet_NaN();
      k.points_camera.emplace_back(i == 1 ? nan : 0.1f * i, 0.2f, i == 1 ? nan : 2.0f);
    }
    k.bow = {{5, 0.25f}, {77, 0.75f}};
    entry.saved.T_base_camera =
        common::Rigid3d(Eigen::Vector3d(0.2, 0.0, 0.5), Eigen::Quaterniond(0.5, -0.5, 0.5, -0.5));
    entry.T_node_base = common::Rigid2d({0.1 * id, -0.05}, 0.01 * id);
    state.keyframes.push_back(entry);
  }
  return state;
}

TEST(VisualKeyframesFileTest, RoundTripIsExact) {
  const VisualKeyframesState state = TwoKeyframes();
  const std::string bytes = EncodeVisualKeyframes(state);
  VisualKeyframesState read;
  std::string error;
  ASSERT_TRUE(DecodeVisualKeyframes(bytes, "kf", &read, &error)) << error;
  ASSERT_EQ(read.keyframes.size(), 2u);
  EXPECT_EQ(read.next_keyframe_id, 9);
  const visual_loop::Keyframe& k = read.keyframes[1].saved.keyframe;
  EXPECT_EQ(k.id, 7);
  EXPECT_EQ(k.node, 70);
  EXPECT_EQ(k.submap, 3);
  EXPECT_EQ(k.keypoints[2].x, 21.0f);
  EXPECT_EQ(k.descriptors.at<uint8_t>(2, 31), static_cast<uint8_t>(7 * 2 + 31));
  EXPECT_EQ(k.vocabulary_nodes[1], 101u);
  EXPECT_TRUE(std::isnan(k.points_camera[1].x()));
  EXPECT_EQ(k.points_camera[2].z(), 2.0f);
  EXPECT_EQ(k.bow[1].first, 77u);
  EXPECT_DOUBLE_EQ(read.keyframes[1].T_node_base.translation().x(), 0.7);
  EXPECT_EQ(EncodeVisualKeyframes(read), bytes);
  // 56 bytes a keypoint (descriptor, position, word, 3D point), 8 a word: no pixels.
  EXPECT_LT(bytes.size(), 24u + 2 * (200 + 3 * 56 + 2 * 8 + 8));
}

TEST(VisualKeyframesFileTest, CorruptInputIsRefusedWithAReason) {
  const std::string bytes = EncodeVisualKeyframes(TwoKeyframes());
  VisualKeyframesState read;
  std::string error;
  EXPECT_FALSE(DecodeVisualKeyframes("junk", "kf", &read, &error));
  EXPECT_NE(error.find("magic"), std::string::npos) << error;
  EXPECT_FALSE(DecodeVisualKeyframes(bytes.substr(0, bytes.size() - 7), "kf", &read, &error));
  EXPECT_NE(error.find("truncated"), std::string::npos) << error;
  std::string flipped = bytes;
  flipped[100] ^= 0x40;
  EXPECT_FALSE(DecodeVisualKeyframes(flipped, "kf", &read, &error));
  EXPECT_NE(error.find("checksum"), std::string::npos) << error;
  std::string version = bytes;
  version[8] = 9;
  EXPECT_FALSE(DecodeVisualKeyframes(version, "kf", &read, &error));
  EXPECT_NE(error.find("version 9"), std::string::npos) << error;
  // Well-formed but inconsistent: an id at or beyond the next id.
  VisualKeyframesState bad = TwoKeyframes();
  bad.next_keyframe_id = 5;
  EXPECT_FALSE(DecodeVisualKeyframes(EncodeVisualKeyframes(bad), "kf", &read, &error));
  EXPECT_NE(error.find("next id"), std::string::npos) << error;
  // Every truncation of the payload with a fixed-up header is refused, never a crash.
  for (size_t cut = 24; cut < bytes.size(); cut += 7) {
    EXPECT_FALSE(DecodeVisualKeyframes(bytes.substr(0, cut), "kf", &read, &error));
  }
}

TEST(VisualKeyframesFileTest, FilesRoundTripAndMissingOnesAreNamed) {
  const std::string path = ::testing::TempDir() + "/visual_keyframes_file_test.fmvk";
  std::string error;
  ASSERT_TRUE(WriteVisualKeyframesFile(path, TwoKeyframes(), &error)) << error;
  VisualKeyframesState read;
  ASSERT_TRUE(ReadVisualKeyframesFile(path, &read, &error)) << error;
  EXPECT_EQ(read.keyframes.size(), 2u);
  EXPECT_FALSE(ReadVisualKeyframesFile(path + ".missing", &read, &error));
  EXPECT_NE(error.find(".missing"), std::string::npos) << error;
}

}  // namespace
}  // namespace io
}  // namespace fusemap
