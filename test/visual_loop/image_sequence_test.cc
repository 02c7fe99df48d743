#include "fusemap/visual_loop/image_sequence.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

namespace fusemap {
namespace visual_loop {
namespace {

TEST(ImageSequenceTest, NaturalOrderComparesNumbersAsNumbers) {
  std::vector<std::string> names = {"10.png", "2.png", "1.png", "img_10.jpg", "img_9.jpg",
                                    "img_009b.jpg", "a.png", "01.png"};
  std::sort(names.begin(), names.end(), NaturalLess);
  const std::vector<std::string> expected = {"1.png", "01.png", "2.png", "10.png", "a.png",
                                             "img_9.jpg", "img_009b.jpg", "img_10.jpg"};
  EXPECT_EQ(names, expected);
  EXPECT_FALSE(NaturalLess("5.png", "5.png"));
  EXPECT_TRUE(NaturalLess("frame99999999999999999999.png", "frame100000000000000000000.png"));
}

TEST(ImageSequenceTest, ListsOnlyImagesInNaturalOrder) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "image_sequence_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "sub.png");
  for (const char* name : {"10.png", "2.PNG", "1.jpg", "notes.txt"}) std::ofstream(dir / name) << "x";
  std::string error;
  const std::vector<std::string> images = ListImages(dir.string(), &error);
  ASSERT_EQ(images.size(), 3u) << error;
  EXPECT_EQ(std::filesystem::path(images[0]).filename(), "1.jpg");
  EXPECT_EQ(std::filesystem::path(images[1]).filename(), "2.PNG");
  EXPECT_EQ(std::filesystem::path(images[2]).filename(), "10.png");
  std::filesystem::remove_all(dir);
  EXPECT_TRUE(ListImages(dir.string(), &error).empty());
  EXPECT_FALSE(error.empty());
}

}  // namespace
}  // namespace visual_loop
}  // namespace fusemap
