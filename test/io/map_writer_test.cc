#include "fusemap/io/map_writer.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

namespace fusemap {
namespace io {
namespace {

class MapWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char dir_template[] = "/tmp/fusemap_map_XXXXXX";
    ASSERT_NE(mkdtemp(dir_template), nullptr);
    dir_ = dir_template;
  }
  void TearDown() override {
    for (const char* name : {"/map.pgm", "/map.yaml", "/map.png"})
      std::remove((dir_ + name).c_str());
    rmdir(dir_.c_str());
  }

  // 4 wide, 3 high; top row occupied, bottom-left pixel free, rest unknown.
  static MapImage SmallMap() {
    MapImage map;
    map.width = 4;
    map.height = 3;
    map.resolution_m = 0.5;
    map.origin_m = Eigen::Vector2d(-1.0, -0.75);
    map.pixels = {0, 0, 0, 0, 205, 205, 205, 205, 254, 205, 205, 205};
    return map;
  }

  static std::string Slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream out;
    out << in.rdbuf();
    return out.str();
  }

  std::string dir_;
};

TEST_F(MapWriterTest, WritesBinaryPgmAndMapServerYaml) {
  std::string error;
  ASSERT_TRUE(WriteMapPgmYaml(SmallMap(), dir_ + "/map", &error)) << error;
  const std::string pgm = Slurp(dir_ + "/map.pgm");
  const std::string header = "P5\n4 3\n255\n";
  ASSERT_EQ(pgm.substr(0, header.size()), header);
  ASSERT_EQ(pgm.size(), header.size() + 12);
  const std::string body = pgm.substr(header.size());
  EXPECT_EQ(std::vector<uint8_t>(body.begin(), body.end()), SmallMap().pixels);

  EXPECT_EQ(Slurp(dir_ + "/map.yaml"),
            "image: map.pgm\nresolution: 0.5\norigin: [-1, -0.75, 0.0]\nnegate: 0\n"
            "occupied_thresh: 0.65\nfree_thresh: 0.196\nmode: trinary\n");
}

TEST_F(MapWriterTest, RejectsInconsistentImage) {
  MapImage map = SmallMap();
  map.pixels.pop_back();
  std::string error;
  EXPECT_FALSE(WriteMapPgmYaml(map, dir_ + "/map", &error));
  EXPECT_NE(error.find("pixel count"), std::string::npos);
  EXPECT_FALSE(WriteMapPgmYaml(SmallMap(), "/nonexistent/dir/map", &error));
  EXPECT_NE(error.find("/nonexistent/dir/map.pgm"), std::string::npos);
}

// An all-free map of width x height cells of 0.1 m, origin at (0, 0), its trajectory drawn
// into DIR/map.png and read back.
cv::Mat DrawFreeMap(int width, int height, const std::vector<Eigen::Vector2d>& xy,
                    const std::string& dir) {
  MapImage map;
  map.width = width;
  map.height = height;
  map.resolution_m = 0.1;
  map.origin_m = Eigen::Vector2d(0.0, 0.0);
  map.pixels.assign(static_cast<size_t>(width) * height, 254);
  std::string error;
  EXPECT_TRUE(WriteMapPng(map, xy, dir + "/map.png", &error)) << error;
  return cv::imread(dir + "/map.png", cv::IMREAD_COLOR);
}

TEST_F(MapWriterTest, PngShowsTrajectoryWithMarkers) {
  // Horizontal line at y = 3.05 m: pixel row 60 - 30.5 - 0.5 = 29 from the top.
  const cv::Mat image =
      DrawFreeMap(100, 60, {{1.05, 3.05}, {5.05, 3.05}, {9.05, 3.05}}, dir_);
  ASSERT_EQ(image.rows, 60);
  ASSERT_EQ(image.cols, 100);
  const cv::Vec3b on_line = image.at<cv::Vec3b>(29, 50);
  EXPECT_GT(on_line[0], 200);  // Blue line (BGR).
  EXPECT_LT(on_line[2], 60);
  const cv::Vec3b off_line = image.at<cv::Vec3b>(10, 50);
  EXPECT_EQ(off_line, cv::Vec3b(254, 254, 254));
  const cv::Vec3b start_ring = image.at<cv::Vec3b>(29 - 4, 10);  // Green ring, radius 4 px.
  EXPECT_GT(start_ring[1], 100);
  EXPECT_LT(start_ring[2], 100);
  const cv::Vec3b end_ring = image.at<cv::Vec3b>(29 - 4, 90);  // Red ring.
  EXPECT_GT(end_ring[2], 150);
  EXPECT_LT(end_ring[1], 100);
}

TEST_F(MapWriterTest, PngOfALargeMapIsShrunkWithTheTrajectoryInPlace) {
  // 9000 x 60 cells are shrunk by 3 to 3000 x 20 pixels. y = 3.0 m is the edge between cell
  // rows 29 and 30 from the top, i.e. between shrunk rows 9 and 10; x = 450 m is shrunk column
  // 1500.
  const cv::Mat image = DrawFreeMap(9000, 60, {{100.0, 3.0}, {450.0, 3.0}, {800.0, 3.0}}, dir_);
  ASSERT_EQ(image.cols, 3000);
  ASSERT_EQ(image.rows, 20);
  const cv::Vec3b near_line = image.at<cv::Vec3b>(9, 1500);
  EXPECT_GT(near_line[0], 200);  // Blue line (BGR).
  EXPECT_LT(near_line[2], 200);
  EXPECT_EQ(image.at<cv::Vec3b>(2, 1500), cv::Vec3b(254, 254, 254));
}

}  // namespace
}  // namespace io
}  // namespace fusemap
