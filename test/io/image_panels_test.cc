#include "fusemap/io/image_panels.h"

#include <gtest/gtest.h>

namespace fusemap {
namespace io {
namespace {

TEST(ImagePanelsTest, SideBySideKeepsBothAtFullSizeWhenTheyFit) {
  const cv::Mat left(50, 100, CV_8UC1, cv::Scalar(0));
  const cv::Mat right(80, 60, CV_8UC3, cv::Scalar(10, 20, 30));
  const cv::Mat out = SideBySide(left, "reference", right, "ours", "title \xc2\xb0 ok");
  ASSERT_EQ(out.type(), CV_8UC3);
  EXPECT_GE(out.cols, 100 + 60);
  // Both images appear unscaled below the two text bands, the right one after the left.
  const int top = out.rows - 10 - 80;
  EXPECT_EQ(out.at<cv::Vec3b>(top + 49, 10 + 99), cv::Vec3b(0, 0, 0));
  EXPECT_EQ(out.at<cv::Vec3b>(top + 50, 10 + 99), cv::Vec3b(255, 255, 255));
  EXPECT_EQ(out.at<cv::Vec3b>(top + 79, 10 + 100 + 10 + 59), cv::Vec3b(10, 20, 30));
}

TEST(ImagePanelsTest, SideBySideShrinksBothByOneFactor) {
  const cv::Mat left(400, 3000, CV_8UC1, cv::Scalar(0));
  const cv::Mat right(400, 1000, CV_8UC1, cv::Scalar(100));
  const cv::Mat out = SideBySide(left, "l", right, "r", "t", /*max_width_px=*/1000);
  EXPECT_LE(out.cols, 1000);
  // The left panel is three times as wide as the right one, as before.
  const int row = out.rows - 11;
  int left_width = 0, right_width = 0;
  for (int col = 0; col < out.cols; ++col) {
    const cv::Vec3b p = out.at<cv::Vec3b>(row, col);
    if (p == cv::Vec3b(0, 0, 0)) ++left_width;
    if (p == cv::Vec3b(100, 100, 100)) ++right_width;
  }
  ASSERT_GT(right_width, 0);
  EXPECT_NEAR(static_cast<double>(left_width) / right_width, 3.0, 0.05);
}

TEST(ImagePanelsTest, ContactSheetTilesRowByRow) {
  const std::vector<cv::Mat> images = {cv::Mat(50, 200, CV_8UC3, cv::Scalar(1, 1, 1)),
                                       cv::Mat(100, 100, CV_8UC3, cv::Scalar(2, 2, 2)),
                                       cv::Mat(20, 100, CV_8UC1, cv::Scalar(3))};
  const cv::Mat sheet = ContactSheet(images, /*columns=*/2, /*cell_width_px=*/100);
  EXPECT_EQ(sheet.cols, 10 + 2 * (100 + 10));
  // Row 1: 25 and 100 px high; row 2: 20 px.
  EXPECT_EQ(sheet.rows, 10 + 100 + 10 + 20 + 10);
  EXPECT_EQ(sheet.at<cv::Vec3b>(10, 10), cv::Vec3b(1, 1, 1));
  EXPECT_EQ(sheet.at<cv::Vec3b>(10, 120), cv::Vec3b(2, 2, 2));
  EXPECT_EQ(sheet.at<cv::Vec3b>(120, 10), cv::Vec3b(3, 3, 3));
  EXPECT_TRUE(ContactSheet({}, 2, 100).empty());
}

TEST(ImagePanelsTest, FilesThatCannotBeReadAreNamed) {
  std::string error;
  EXPECT_FALSE(WriteSideBySideFile("/nonexistent/a.png", "a", "/nonexistent/b.png", "b", "t",
                                   testing::TempDir() + "/out.png", &error));
  EXPECT_NE(error.find("/nonexistent/a.png"), std::string::npos) << error;
}

}  // namespace
}  // namespace io
}  // namespace fusemap
