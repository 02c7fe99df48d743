#include "fusemap/io/visual_loop_config.h"

#include <gtest/gtest.h>

#include <string>

#include "fusemap/io/slam_config.h"

namespace fusemap {
namespace io {
namespace {

// Parses `yaml` as a whole SLAM config; false with the reader's report otherwise.
bool Parse(const std::string& yaml, SlamConfig* config, std::string* error) {
  auto reader = common::ConfigReader::FromString(yaml, "test.yaml", error);
  if (!reader) return false;
  ParseSlamConfig(*reader, config);
  return reader->Finish(error);
}

TEST(VisualLoopConfigTest, OffByDefaultWithTheProjectVocabularyPath) {
  SlamConfig config;
  std::string error;
  ASSERT_TRUE(Parse("", &config, &error)) << error;
  EXPECT_FALSE(config.visual_loop.enabled);
  EXPECT_EQ(config.visual_loop.vocabulary, "data/vocabulary/orb_k10_l4.bin");
  EXPECT_EQ(config.visual_loop.loaded_vocabulary, nullptr);  // not loaded while off
  EXPECT_TRUE(config.visual_loop.IsValid(&error)) << error;
}

TEST(VisualLoopConfigTest, EnabledLoadsTheVocabularyRelativeToTheSourceTree) {
  SlamConfig config;
  std::string error;
  ASSERT_TRUE(
      Parse("visual_loop:\n"
            "  enabled: true\n"
            "  max_queue_frames: 4\n"
            "  keyframes: {min_translation_m: 0.5, max_features: 800}\n"
            "  recognition: {temporal_consistency: 1}\n"
            "  verification: {min_inliers: 40}\n"
            "  arbitration: {max_translation_disagreement_m: 0.2,\n"
            "                max_laser_explained_fraction: 0.7}\n"
            "  motion_links: {enabled: false, translation_weight: 5e4,\n"
            "                 max_disagreement_m: 0.1, refine_on_pixels: false}\n",
            &config, &error))
      << error;
  const VisualLoopConfig& v = config.visual_loop;
  ASSERT_NE(v.loaded_vocabulary, nullptr);
  EXPECT_GT(v.loaded_vocabulary->num_words(), 1000);
  EXPECT_EQ(v.max_queue_frames, 4);
  EXPECT_EQ(v.checker.selector.min_translation_m, 0.5);
  EXPECT_EQ(v.checker.orb.max_features, 800);
  EXPECT_EQ(v.checker.detector.recognition.temporal_consistency, 1);
  EXPECT_EQ(v.checker.detector.verification.min_inliers, 40);
  EXPECT_EQ(v.arbitration.max_translation_disagreement_m, 0.2);
  EXPECT_EQ(v.arbitration.max_laser_explained_fraction, 0.7);
  EXPECT_FALSE(v.motion_links.enabled);
  EXPECT_EQ(v.motion_links.translation_weight, 5e4);
  EXPECT_EQ(v.motion_links.max_disagreement_m, 0.1);
  EXPECT_EQ(v.motion_links.max_disagreement_rad, MotionLinkOptions().max_disagreement_rad);
  EXPECT_FALSE(v.checker.refine_latest_on_pixels);
  EXPECT_TRUE(visual_loop::VisualLoopCheckerOptions().refine_latest_on_pixels);
  EXPECT_EQ(ResolveVocabularyPath("/abs/v.bin"), "/abs/v.bin");
  EXPECT_EQ(ResolveVocabularyPath("data/v.bin"), std::string(FUSEMAP_SOURCE_DIR) + "/data/v.bin");
}

TEST(VisualLoopConfigTest, BadValuesAreRefusedWithKeyPathAndLine) {
  SlamConfig config;
  std::string error;
  EXPECT_FALSE(Parse("visual_loop:\n"
                     "  enabled: false\n"
                     "  verification:\n"
                     "    min_inliers: 2\n",
                     &config, &error));
  EXPECT_NE(error.find("visual_loop.verification.min_inliers"), std::string::npos) << error;
  EXPECT_NE(error.find("test.yaml:4"), std::string::npos) << error;

  EXPECT_FALSE(Parse("visual_loop:\n  arbitration: {max_laser_explained_fraction: 1.5}\n",
                     &config, &error));
  EXPECT_NE(error.find("visual_loop.arbitration.max_laser_explained_fraction"), std::string::npos)
      << error;

  EXPECT_FALSE(Parse("visual_loop:\n  max_queue_frames: 0\n", &config, &error));
  EXPECT_NE(error.find("visual_loop.max_queue_frames"), std::string::npos) << error;

  EXPECT_FALSE(Parse("visual_loop:\n  motion_links: {rotation_weight: 0}\n", &config, &error));
  EXPECT_NE(error.find("visual_loop.motion_links.rotation_weight"), std::string::npos) << error;

  EXPECT_FALSE(Parse("visual_loop:\n  keyfrmaes: {}\n", &config, &error));
  EXPECT_NE(error.find("visual_loop.keyfrmaes"), std::string::npos) << error;
}

TEST(VisualLoopConfigTest, AMissingVocabularyIsAnErrorOnlyWhenEnabled) {
  SlamConfig config;
  std::string error;
  EXPECT_TRUE(Parse("visual_loop: {vocabulary: /nonexistent/v.bin}\n", &config, &error)) << error;
  EXPECT_FALSE(Parse("visual_loop: {enabled: true, vocabulary: /nonexistent/v.bin}\n", &config,
                     &error));
  EXPECT_NE(error.find("visual_loop.vocabulary"), std::string::npos) << error;
  EXPECT_NE(error.find("/nonexistent/v.bin"), std::string::npos) << error;
}

}  // namespace
}  // namespace io
}  // namespace fusemap
