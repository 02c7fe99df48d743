#include "fusemap/io/cloud_image.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <cstdio>
#include <string>

namespace fusemap {
namespace io {
namespace {

std::string TempPath(const std::string& name) {
  return ::testing::TempDir() + "/" + name;
}

TEST(CloudImageTest, NearSurfaceHidesFarOneAndClipRemovesCeiling) {
  cloud::ColorCloud cloud;
  // A red square on the floor, a green one 1 m above it (nearer a viewer looking down) and a
  // blue "ceiling" above the clip height.
  for (int i = 0; i < 50; ++i) {
    for (int j = 0; j < 50; ++j) {
      cloud::ColorPoint p;
      p.x = 0.02f * i;
      p.y = 0.02f * j;
      p.z = 0.0f;
      p.r = 255, p.g = 0, p.b = 0;
      cloud.push_back(p);
      p.z = 1.0f, p.r = 0, p.g = 255, p.b = 0;
      cloud.push_back(p);
      p.z = 3.0f, p.r = 0, p.g = 0, p.b = 255;
      cloud.push_back(p);
    }
  }
  CloudImageOptions options;
  options.width_px = 200;
  options.elevation_deg = 90.0;  // Straight down: green covers red exactly.
  const std::string path = TempPath("cloud_image_test.png");
  std::string error;
  ASSERT_TRUE(WriteCloudPng(cloud, options, path, &error)) << error;
  const cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
  ASSERT_FALSE(image.empty());
  EXPECT_EQ(image.cols, 200);
  int green = 0, red = 0, blue = 0;
  for (int v = 0; v < image.rows; ++v) {
    for (int u = 0; u < image.cols; ++u) {
      const cv::Vec3b c = image.at<cv::Vec3b>(v, u);
      green += c[1] == 255;
      red += c[2] == 255;
      blue += c[0] == 255;
    }
  }
  EXPECT_GE(green, 9000);  // 50 x 50 splats of 2 x 2 pixels
  EXPECT_EQ(red, 0);
  EXPECT_EQ(blue, 0);
  std::remove(path.c_str());
}

TEST(CloudImageTest, EmptyCloudAndBadPathAreErrors) {
  std::string error;
  cloud::ColorCloud cloud;
  EXPECT_FALSE(WriteCloudPng(cloud, CloudImageOptions(), TempPath("empty.png"), &error));
  EXPECT_NE(error.find("empty"), std::string::npos);
  cloud::ColorPoint p;
  p.x = p.y = p.z = 0.0f;
  cloud.push_back(p);
  EXPECT_FALSE(WriteCloudPng(cloud, CloudImageOptions(), "/nonexistent-dir/x.png", &error));
  EXPECT_NE(error.find("/nonexistent-dir/x.png"), std::string::npos);
}

}  // namespace
}  // namespace io
}  // namespace fusemap
