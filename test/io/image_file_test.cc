#include "fusemap/io/image_file.h"

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

namespace fusemap {
namespace io {
namespace {

std::string WriteBytes(const std::string& name, const std::vector<uint8_t>& bytes) {
  const std::string path = ::testing::TempDir() + "image_file_test_" + name;
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                              static_cast<std::streamsize>(bytes.size()));
  return path;
}

TEST(ImageFileTest, ReadsAPngAndAJpeg) {
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(cv::imencode(".png", cv::Mat(12, 34, CV_8UC1, cv::Scalar(7)), bytes));
  cv::Mat image;
  std::string error;
  ASSERT_TRUE(ReadImageFile(WriteBytes("ok.png", bytes), cv::IMREAD_GRAYSCALE, 100, &image, &error)) << error;
  EXPECT_EQ(image.cols, 34);
  EXPECT_EQ(image.rows, 12);
  ASSERT_TRUE(cv::imencode(".jpg", cv::Mat(12, 34, CV_8UC3, cv::Scalar(7, 8, 9)), bytes));
  ASSERT_TRUE(ReadImageFile(WriteBytes("ok.jpg", bytes), cv::IMREAD_COLOR, 100, &image, &error)) << error;
  EXPECT_EQ(image.channels(), 3);
}

// Issue 18, items 2 and 5: a PNG header declaring 65500 x 65500 aborted fusemap_tagscore inside
// OpenCV, and 20000 x 20000 took 32 s; the declared size is checked before decoding.
TEST(ImageFileTest, RefusesHugeDeclaredSizesDirectoriesAndOtherFormatsQuickly) {
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(cv::imencode(".png", cv::Mat(2, 2, CV_8UC1, cv::Scalar(7)), bytes));
  cv::Mat image;
  std::string error;
  for (uint8_t high : {0xff, 0x4e}) {  // 65535-ish and 20000-ish (0x4e20 = 20000)
    std::vector<uint8_t> huge = bytes;
    huge[18] = huge[22] = high;  // IHDR width and height, big-endian, second-lowest bytes
    huge[19] = huge[23] = 0x20;
    const std::string path = WriteBytes("huge.png", huge);
    const auto start = std::chrono::steady_clock::now();
    EXPECT_FALSE(ReadImageFile(path, cv::IMREAD_GRAYSCALE, 8192, &image, &error));
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
    EXPECT_NE(error.find(path + ": declares"), std::string::npos) << error;
  }
  EXPECT_FALSE(ReadImageFile(::testing::TempDir(), cv::IMREAD_GRAYSCALE, 8192, &image, &error));
  EXPECT_NE(error.find("is a directory"), std::string::npos) << error;
  EXPECT_FALSE(ReadImageFile(WriteBytes("x.bmp", {'B', 'M', 1, 2, 3}), cv::IMREAD_GRAYSCALE, 8192, &image, &error));
  EXPECT_NE(error.find("neither PNG nor JPEG"), std::string::npos) << error;
  EXPECT_FALSE(ReadImageFile(WriteBytes("empty.png", {}), cv::IMREAD_GRAYSCALE, 8192, &image, &error));
  EXPECT_FALSE(ReadImageFile("/nonexistent/x.png", cv::IMREAD_GRAYSCALE, 8192, &image, &error));
}

}  // namespace
}  // namespace io
}  // namespace fusemap
