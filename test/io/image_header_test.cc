#include "image_header.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

namespace fusemap {
namespace io {
namespace {

std::vector<uint8_t> Encode(const cv::Mat& image, const std::string& ext) {
  std::vector<uint8_t> bytes;
  EXPECT_TRUE(cv::imencode(ext, image, bytes));
  return bytes;
}

TEST(ImageHeaderTest, ReadsPngAndJpegSizesWithoutDecoding) {
  ImageHeader header;
  std::string error;
  const auto png16 = Encode(cv::Mat(7, 13, CV_16UC1, cv::Scalar(1000)), ".png");
  ASSERT_TRUE(ReadImageHeader(png16.data(), png16.size(), &header, &error)) << error;
  EXPECT_EQ(header.format, ImageHeader::Format::kPng);
  EXPECT_EQ(header.width, 13);
  EXPECT_EQ(header.height, 7);
  EXPECT_EQ(header.bit_depth, 16);
  EXPECT_EQ(header.channels, 1);
  const auto png_rgb = Encode(cv::Mat(3, 5, CV_8UC3, cv::Scalar(1, 2, 3)), ".png");
  ASSERT_TRUE(ReadImageHeader(png_rgb.data(), png_rgb.size(), &header, &error)) << error;
  EXPECT_EQ(header.channels, 3);
  EXPECT_EQ(header.bit_depth, 8);
  const auto jpeg = Encode(cv::Mat(48, 64, CV_8UC3, cv::Scalar(10, 200, 30)), ".jpg");
  ASSERT_TRUE(ReadImageHeader(jpeg.data(), jpeg.size(), &header, &error)) << error;
  EXPECT_EQ(header.format, ImageHeader::Format::kJpeg);
  EXPECT_EQ(header.width, 64);
  EXPECT_EQ(header.height, 48);
  EXPECT_EQ(header.channels, 3);
}

TEST(ImageHeaderTest, RejectsEmptyTruncatedAndForeignBytes) {
  ImageHeader header;
  std::string error;
  EXPECT_FALSE(ReadImageHeader(nullptr, 0, &header, &error));
  EXPECT_EQ(error, "image is empty");
  const uint8_t bmp[] = {'B', 'M', 0, 0, 0, 0};
  EXPECT_FALSE(ReadImageHeader(bmp, sizeof(bmp), &header, &error));
  EXPECT_NE(error.find("neither PNG nor JPEG"), std::string::npos) << error;
  const auto png = Encode(cv::Mat(7, 13, CV_8UC1, cv::Scalar(1)), ".png");
  const auto jpeg = Encode(cv::Mat(8, 8, CV_8UC1, cv::Scalar(1)), ".jpg");
  // Every truncation before the size fields is refused, none reads past the end.
  for (size_t n = 1; n < 24; ++n) EXPECT_FALSE(ReadImageHeader(png.data(), n, &header, &error)) << n;
  size_t jpeg_ok_from = jpeg.size();
  for (size_t n = 1; n < jpeg.size(); ++n) {
    if (ReadImageHeader(jpeg.data(), n, &header, &error)) {
      jpeg_ok_from = n;
      break;
    }
  }
  EXPECT_LT(jpeg_ok_from, jpeg.size());
  // A zero size is corrupt.
  std::vector<uint8_t> zero = png;
  zero[16] = zero[17] = zero[18] = zero[19] = 0;
  EXPECT_FALSE(ReadImageHeader(zero.data(), zero.size(), &header, &error));
}

}  // namespace
}  // namespace io
}  // namespace fusemap
