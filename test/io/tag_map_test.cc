#include "fusemap/io/tag_map.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace fusemap {
namespace io {
namespace {

namespace fs = std::filesystem;

std::string WriteTemp(const std::string& name, const std::string& text) {
  const fs::path path = fs::temp_directory_path() / ("fusemap_tag_map_test_" + name);
  std::ofstream(path) << text;
  return path.string();
}

TEST(TagMapTest, ReadsTagsWithDefaultsAndRotation) {
  const std::string path = WriteTemp("ok.yaml",
                                     "tag_size_m: 0.16\n"
                                     "tags:\n"
                                     "  - {id: 0, x_m: 0.3, y_m: 0.3}\n"
                                     "  - {id: 4, x_m: 0.9, y_m: 0.3, z_m: 0.01, yaw_deg: 90, "
                                     "size_m: 0.15}\n");
  ground_truth::TagMap tags;
  std::string error;
  ASSERT_TRUE(ReadTagMapFile(path, 0.0, &tags, &error)) << error;
  ASSERT_EQ(tags.size(), 2u);
  EXPECT_DOUBLE_EQ(tags.at(0).size_m, 0.16);
  EXPECT_DOUBLE_EQ(tags.at(4).size_m, 0.15);
  // yaw 90 deg: the tag's x axis points along map +y.
  const Eigen::Vector3d x_axis = tags.at(4).T_map_tag.rotation() * Eigen::Vector3d::UnitX();
  EXPECT_LT((x_axis - Eigen::Vector3d::UnitY()).norm(), 1e-12);
  EXPECT_LT((tags.at(4).T_map_tag.translation() - Eigen::Vector3d(0.9, 0.3, 0.01)).norm(), 1e-12);
}

TEST(TagMapTest, DuplicateIdNamesFileAndLine) {
  const std::string path = WriteTemp("dup.yaml",
                                     "tags:\n"
                                     "  - {id: 2, x_m: 0.3, y_m: 0.3}\n"
                                     "  - {id: 3, x_m: 0.9, y_m: 0.3}\n"
                                     "  - {id: 2, x_m: 1.5, y_m: 0.3}\n");
  ground_truth::TagMap tags;
  std::string error;
  EXPECT_FALSE(ReadTagMapFile(path, 0.16, &tags, &error));
  EXPECT_NE(error.find(path + ":4: duplicate tag id 2 (first listed at line 2)"), std::string::npos)
      << error;
}

TEST(TagMapTest, BadInputIsReported) {
  ground_truth::TagMap tags;
  std::string error;
  EXPECT_FALSE(ReadTagMapFile("/nonexistent/tags.yaml", 0.16, &tags, &error));
  EXPECT_NE(error.find("/nonexistent/tags.yaml"), std::string::npos);
  const std::string unknown =
      WriteTemp("unknown.yaml", "tags:\n  - {id: 1, x_m: 0, y_m: 0, yaw: 3}\n");
  EXPECT_FALSE(ReadTagMapFile(unknown, 0.16, &tags, &error));
  EXPECT_NE(error.find(":2: unknown key 'yaw'"), std::string::npos) << error;
  const std::string no_size = WriteTemp("nosize.yaml", "tags:\n  - {id: 1, x_m: 0, y_m: 0}\n");
  EXPECT_FALSE(ReadTagMapFile(no_size, 0.0, &tags, &error));
  EXPECT_NE(error.find("size_m"), std::string::npos) << error;
  const std::string not_number = WriteTemp("nan.yaml", "tags:\n  - {id: 1, x_m: abc, y_m: 0}\n");
  EXPECT_FALSE(ReadTagMapFile(not_number, 0.16, &tags, &error));
  EXPECT_NE(error.find(":2: expected a number"), std::string::npos) << error;
}

TEST(TagMapTest, WriteReadRoundTrip) {
  ground_truth::TagMap tags;
  tags[7] = {7, 0.2,
             common::Rigid3d(Eigen::Vector3d(1.2, -0.6, 0.0),
                             Eigen::Quaterniond(Eigen::AngleAxisd(-2.0, Eigen::Vector3d::UnitZ()) *
                                                Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX())))};
  const std::string path = (fs::temp_directory_path() / "fusemap_tag_map_rt.yaml").string();
  std::string error;
  ASSERT_TRUE(WriteTagMapFile(path, tags, &error)) << error;
  ground_truth::TagMap back;
  ASSERT_TRUE(ReadTagMapFile(path, 0.0, &back, &error)) << error;
  ASSERT_EQ(back.size(), 1u);
  EXPECT_DOUBLE_EQ(back.at(7).size_m, 0.2);
  EXPECT_LT(back.at(7).T_map_tag.rotation().angularDistance(tags[7].T_map_tag.rotation()), 1e-8);
  EXPECT_LT((back.at(7).T_map_tag.translation() - tags[7].T_map_tag.translation()).norm(), 1e-9);
}

TEST(TagMapTest, MeasuresFile) {
  const std::string path = WriteTemp("measures.yaml",
                                     "points: {door: [1.0, 2.0], pillar: [4.0, 6.0]}\n"
                                     "measures:\n"
                                     "  - {from: door, to: pillar, distance_m: 5.01}\n");
  std::vector<ground_truth::MapMeasure> measures;
  std::string error;
  ASSERT_TRUE(ReadMeasuresFile(path, &measures, &error)) << error;
  ASSERT_EQ(measures.size(), 1u);
  EXPECT_DOUBLE_EQ(measures[0].measured_m, 5.01);
  EXPECT_EQ(measures[0].to_map, Eigen::Vector2d(4.0, 6.0));
  const std::string bad = WriteTemp("measures_bad.yaml",
                                    "points: {door: [1.0, 2.0]}\n"
                                    "measures:\n"
                                    "  - {from: door, to: window, distance_m: 5.01}\n");
  EXPECT_FALSE(ReadMeasuresFile(bad, &measures, &error));
  EXPECT_NE(error.find(":3: unknown point 'window'"), std::string::npos) << error;
}

TEST(TagMapTest, SightingsRoundTripAndBadLine) {
  std::vector<ground_truth::TagSighting> sightings = {
      {12.5, 3, common::Rigid3d(Eigen::Vector3d(1, 2, 0), Eigen::Quaterniond::Identity())}};
  const std::string path = (fs::temp_directory_path() / "fusemap_sightings.txt").string();
  std::string error;
  ASSERT_TRUE(WriteTagSightingsFile(path, sightings, &error)) << error;
  std::vector<ground_truth::TagSighting> back;
  ASSERT_TRUE(ReadTagSightingsFile(path, &back, &error)) << error;
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].tag_id, 3);
  EXPECT_DOUBLE_EQ(back[0].stamp_s, 12.5);
  const std::string bad = WriteTemp("sightings_bad.txt", "# header\n1.0 3 1 2 0 0 0 0\n");
  EXPECT_FALSE(ReadTagSightingsFile(bad, &back, &error));
  EXPECT_NE(error.find(":2:"), std::string::npos) << error;
}

}  // namespace
}  // namespace io
}  // namespace fusemap
