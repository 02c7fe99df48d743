#include "ply_header.h"

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>

#include "fusemap/io/cloud_writer.h"

namespace fusemap {
namespace io {
namespace {

std::string Write(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "ply_header_test_" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

TEST(PlyHeaderTest, AcceptsWhatTheWriterWritesAndSmallAsciiFiles) {
  cloud::ColorCloud cloud;
  for (int i = 0; i < 10; ++i) {
    cloud::ColorPoint p(uint8_t{1}, uint8_t{2}, uint8_t{3});
    p.x = 0.5f * i;
    cloud.push_back(p);
  }
  const std::string path = ::testing::TempDir() + "ply_header_test_ok.ply";
  std::string error;
  ASSERT_TRUE(WriteCloudPly(path, cloud, &error)) << error;
  EXPECT_TRUE(CheckPlyFileSize(path, &error)) << error;
  cloud::ColorCloud read;
  EXPECT_TRUE(ReadCloudPly(path, &read, &error)) << error;
  EXPECT_EQ(read.size(), 10u);
  EXPECT_TRUE(CheckPlyFileSize(
      Write("ascii.ply", "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\n"
                         "property float y\nend_header\n1 2\n3 4\n"),
      &error))
      << error;
}

// Issue 18, item 14: a header claiming 1e9 vertices took 46 s to be rejected.
TEST(PlyHeaderTest, RefusesCountsTheFileCannotHoldQuickly) {
  std::string error;
  const std::string huge = Write(
      "huge.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\n"
                  "property float x\nproperty float y\nproperty float z\nend_header\n" +
                      std::string(120, '\0'));
  const auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(CheckPlyFileSize(huge, &error));
  EXPECT_NE(error.find("declares 1000000000 vertex elements"), std::string::npos) << error;
  cloud::ColorCloud cloud;
  EXPECT_FALSE(ReadCloudPly(huge, &cloud, &error));
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
  // Two elements that each fit but not together; an ASCII file too short for its count.
  EXPECT_FALSE(CheckPlyFileSize(
      Write("two.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty double x\n"
                       "element face 2\nproperty int n\nend_header\n" + std::string(20, '\0')),
      &error));
  EXPECT_FALSE(CheckPlyFileSize(
      Write("ascii.ply", "ply\nformat ascii 1.0\nelement vertex 30\nproperty float x\nend_header\n1\n"),
      &error));
  // Not PLY, no end of header, a directory.
  EXPECT_FALSE(CheckPlyFileSize(Write("no.ply", "solid x\n"), &error));
  EXPECT_NE(error.find("not a PLY file"), std::string::npos) << error;
  EXPECT_FALSE(CheckPlyFileSize(Write("open.ply", "ply\nformat ascii 1.0\n"), &error));
  EXPECT_NE(error.find("no end_header"), std::string::npos) << error;
  EXPECT_FALSE(CheckPlyFileSize(::testing::TempDir(), &error));
  EXPECT_NE(error.find("is a directory"), std::string::npos) << error;
}

}  // namespace
}  // namespace io
}  // namespace fusemap
