#include "fusemap/visual_loop/vocabulary.h"

#include <chrono>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "fusemap/visual_loop/vocabulary_trainer.h"
#include "visual_loop/vocabulary_test_util.h"

namespace fusemap {
namespace visual_loop {
namespace {

Vocabulary SmallVocabulary(std::vector<cv::Mat>* images_out = nullptr) {
  std::mt19937 rng(11);
  std::vector<cv::Mat> images;
  for (int i = 0; i < 8; ++i) {
    std::vector<OrbDescriptor> image;
    for (int j = 0; j < 100; ++j) image.push_back(testing::RandomDescriptor(&rng));
    images.push_back(testing::ToMat(image));
  }
  VocabularyTrainingOptions options;
  options.branching = 5;
  options.levels = 2;
  if (images_out != nullptr) *images_out = images;
  return TrainVocabulary(images, options);
}

TEST(VocabularyTest, BytesRoundTripGivesTheSameWordsAndWeights) {
  std::vector<cv::Mat> images;
  const Vocabulary vocabulary = SmallVocabulary(&images);
  std::string error;
  const std::optional<Vocabulary> loaded = Vocabulary::FromBytes(vocabulary.ToBytes(), &error);
  ASSERT_TRUE(loaded) << error;
  EXPECT_EQ(loaded->num_words(), vocabulary.num_words());
  EXPECT_EQ(loaded->branching(), 5);
  EXPECT_EQ(loaded->levels(), 2);
  for (const cv::Mat& image : images) EXPECT_EQ(loaded->Transform(image), vocabulary.Transform(image));
}

TEST(VocabularyTest, SaveAndLoadAFile) {
  const Vocabulary vocabulary = SmallVocabulary();
  const std::string path = ::testing::TempDir() + "/vocabulary_test.bin";
  std::string error;
  ASSERT_TRUE(vocabulary.Save(path, &error)) << error;
  const std::optional<Vocabulary> loaded = Vocabulary::Load(path, &error);
  ASSERT_TRUE(loaded) << error;
  EXPECT_EQ(loaded->ToBytes(), vocabulary.ToBytes());
  std::filesystem::remove(path);
  EXPECT_FALSE(Vocabulary::Load(path, &error));
  EXPECT_NE(error.find("cannot open"), std::string::npos) << error;
}

TEST(VocabularyTest, CorruptTruncatedAndForeignFilesAreRefusedWithAReason) {
  const std::vector<uint8_t> bytes = SmallVocabulary().ToBytes();
  std::string error;

  std::vector<uint8_t> flipped = bytes;
  flipped[bytes.size() / 2] ^= 0x10;
  EXPECT_FALSE(Vocabulary::FromBytes(flipped, &error));
  EXPECT_NE(error.find("CRC"), std::string::npos) << error;

  const std::vector<uint8_t> truncated(bytes.begin(), bytes.end() - 7);
  EXPECT_FALSE(Vocabulary::FromBytes(truncated, &error));
  EXPECT_NE(error.find("truncated"), std::string::npos) << error;

  const std::vector<uint8_t> header_only(bytes.begin(), bytes.begin() + 10);
  EXPECT_FALSE(Vocabulary::FromBytes(header_only, &error));

  std::vector<uint8_t> foreign = bytes;
  foreign[0] = '%';  // a YAML vocabulary, say
  EXPECT_FALSE(Vocabulary::FromBytes(foreign, &error));
  EXPECT_NE(error.find("magic"), std::string::npos) << error;

  std::vector<uint8_t> future = bytes;
  future[8] = 99;
  EXPECT_FALSE(Vocabulary::FromBytes(future, &error));
  EXPECT_NE(error.find("version"), std::string::npos) << error;
}

TEST(VocabularyTest, CommittedVocabularyLoadsWellUnderASecond) {
  const std::string path = std::string(FUSEMAP_SOURCE_DIR) + "/data/vocabulary/orb_k10_l4.bin";
  const auto start = std::chrono::steady_clock::now();
  std::string error;
  const std::optional<Vocabulary> vocabulary = Vocabulary::Load(path, &error);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_TRUE(vocabulary) << error;
  EXPECT_EQ(vocabulary->branching(), 10);
  EXPECT_EQ(vocabulary->levels(), 4);
  EXPECT_GT(vocabulary->num_words(), 5000);
  EXPECT_LT(seconds, 0.5);
}

}  // namespace
}  // namespace visual_loop
}  // namespace fusemap
