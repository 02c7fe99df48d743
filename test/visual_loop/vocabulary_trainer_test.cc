#include "fusemap/visual_loop/vocabulary_trainer.h"

#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "visual_loop/vocabulary_test_util.h"

namespace fusemap {
namespace visual_loop {
namespace {

// 10 well separated centres; image i holds noisy copies of centres i % 10 and (i + 1) % 10.
std::vector<cv::Mat> ClusteredImages(std::vector<OrbDescriptor>* centres) {
  std::mt19937 rng(3);
  for (int c = 0; c < 10; ++c) centres->push_back(testing::RandomDescriptor(&rng));
  std::vector<cv::Mat> images;
  for (int i = 0; i < 20; ++i) {
    std::vector<OrbDescriptor> image;
    for (int j = 0; j < 30; ++j) {
      image.push_back(testing::FlipBits((*centres)[(i + j % 2) % 10], 10, &rng));
    }
    images.push_back(testing::ToMat(image));
  }
  return images;
}

TEST(VocabularyTrainerTest, OneLevelFindsTheClusters) {
  std::vector<OrbDescriptor> centres;
  const std::vector<cv::Mat> images = ClusteredImages(&centres);
  VocabularyTrainingOptions options;
  options.branching = 10;
  options.levels = 1;
  const Vocabulary vocabulary = TrainVocabulary(images, options);
  std::string error;
  ASSERT_TRUE(vocabulary.IsConsistent(&error)) << error;
  EXPECT_EQ(vocabulary.num_words(), 10);
  // Each centre has its own word, and noisy copies land on their centre's word.
  std::set<int> words;
  std::mt19937 rng(9);
  for (const OrbDescriptor& centre : centres) {
    const int word = vocabulary.WordOf(centre.data());
    words.insert(word);
    for (int k = 0; k < 5; ++k) {
      EXPECT_EQ(vocabulary.WordOf(testing::FlipBits(centre, 12, &rng).data()), word);
    }
  }
  EXPECT_EQ(words.size(), 10u);
  // Every word occurs in 4 of the 20 images: idf = ln(20 / 4).
  for (int w = 0; w < vocabulary.num_words(); ++w) {
    EXPECT_NEAR(vocabulary.word_weight(w), std::log(5.0), 1e-5);
  }
}

TEST(VocabularyTrainerTest, SameSeedSameVocabularyAndDeeperTreesStayConsistent) {
  std::vector<OrbDescriptor> centres;
  const std::vector<cv::Mat> images = ClusteredImages(&centres);
  VocabularyTrainingOptions options;
  options.branching = 4;
  options.levels = 3;
  const Vocabulary a = TrainVocabulary(images, options);
  const Vocabulary b = TrainVocabulary(images, options);
  EXPECT_EQ(a.ToBytes(), b.ToBytes());
  std::string error;
  EXPECT_TRUE(a.IsConsistent(&error)) << error;
  EXPECT_LE(a.num_words(), 64);
  options.seed = 2;
  EXPECT_TRUE(TrainVocabulary(images, options).IsConsistent(&error)) << error;
}

TEST(VocabularyTrainerTest, WordsInEveryImageWeighNothing) {
  std::mt19937 rng(5);
  const OrbDescriptor everywhere = testing::RandomDescriptor(&rng);
  const OrbDescriptor rare = testing::RandomDescriptor(&rng);
  std::vector<cv::Mat> images;
  for (int i = 0; i < 4; ++i) {
    std::vector<OrbDescriptor> image(5, everywhere);
    if (i == 0) image.push_back(rare);
    images.push_back(testing::ToMat(image));
  }
  VocabularyTrainingOptions options;
  options.branching = 2;
  options.levels = 1;
  const Vocabulary vocabulary = TrainVocabulary(images, options);
  EXPECT_NEAR(vocabulary.word_weight(vocabulary.WordOf(everywhere.data())), 0.0, 1e-6);
  EXPECT_NEAR(vocabulary.word_weight(vocabulary.WordOf(rare.data())), std::log(4.0), 1e-5);
  // A zero-weight word is left out of BoW vectors.
  const BowVector bow = vocabulary.Transform(images[1]);
  EXPECT_TRUE(bow.empty());
}

}  // namespace
}  // namespace visual_loop
}  // namespace fusemap
