#include "fusemap/io/cloud_writer.h"

#include <gtest/gtest.h>
#include <octomap/ColorOcTree.h>
#include <octomap/OcTree.h>

#include <filesystem>
#include <memory>

namespace fusemap {
namespace io {
namespace {

namespace fs = std::filesystem;

std::string TempPath(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "fusemap_cloud_writer_test";
  fs::create_directories(dir);
  return (dir / name).string();
}

cloud::ColorCloud SmallCloud() {
  cloud::ColorCloud cloud;
  for (int i = 0; i < 37; ++i) {
    cloud::ColorPoint p(static_cast<uint8_t>(7 * i), static_cast<uint8_t>(255 - 3 * i),
                        static_cast<uint8_t>(i));
    p.x = 0.125f * i - 2.0f;
    p.y = 0.01f * i * i;
    p.z = -1.5f + 0.3f * (i % 5);
    cloud.push_back(p);
  }
  return cloud;
}

void ExpectSameCloud(const cloud::ColorCloud& a, const cloud::ColorCloud& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_FLOAT_EQ(a[i].x, b[i].x) << i;
    EXPECT_FLOAT_EQ(a[i].y, b[i].y) << i;
    EXPECT_FLOAT_EQ(a[i].z, b[i].z) << i;
    EXPECT_EQ(a[i].r, b[i].r) << i;
    EXPECT_EQ(a[i].g, b[i].g) << i;
    EXPECT_EQ(a[i].b, b[i].b) << i;
  }
}

TEST(CloudWriterTest, PlyRoundTripKeepsPointsAndColours) {
  const cloud::ColorCloud cloud = SmallCloud();
  const std::string path = TempPath("round_trip.ply");
  std::string error;
  ASSERT_TRUE(WriteCloudPly(path, cloud, &error)) << error;
  cloud::ColorCloud read;
  ASSERT_TRUE(ReadCloudPly(path, &read, &error)) << error;
  ExpectSameCloud(cloud, read);
}

TEST(CloudWriterTest, PcdRoundTripKeepsPointsAndColours) {
  const cloud::ColorCloud cloud = SmallCloud();
  const std::string path = TempPath("round_trip.pcd");
  std::string error;
  ASSERT_TRUE(WriteCloudPcd(path, cloud, &error)) << error;
  cloud::ColorCloud read;
  ASSERT_TRUE(ReadCloudPcd(path, &read, &error)) << error;
  ExpectSameCloud(cloud, read);
}

TEST(CloudWriterTest, EmptyCloudRoundTrips) {
  std::string error;
  const std::string path = TempPath("empty.pcd");
  ASSERT_TRUE(WriteCloudPcd(path, cloud::ColorCloud(), &error)) << error;
  cloud::ColorCloud read;
  ASSERT_TRUE(ReadCloudPcd(path, &read, &error)) << error;
  EXPECT_TRUE(read.empty());
}

// Issue 18 item 9: with nothing removed as dynamic, cloud_removed.ply failed to write and the
// run exited 1 without its OctoMap and cloud.png. An empty cloud is a valid empty PLY.
TEST(CloudWriterTest, EmptyPlyRoundTrips) {
  std::string error;
  const std::string path = TempPath("empty.ply");
  ASSERT_TRUE(WriteCloudPly(path, cloud::ColorCloud(), &error)) << error;
  cloud::ColorCloud read = SmallCloud();
  ASSERT_TRUE(ReadCloudPly(path, &read, &error)) << error;
  EXPECT_TRUE(read.empty());
  EXPECT_FALSE(fs::exists(path + ".tmp"));
  // The OctoMaps of an empty cloud: empty trees (ColorOcTree crashed on its missing root).
  ASSERT_TRUE(WriteOctoMaps(cloud::ColorCloud(), 0.05, TempPath("empty.bt"), TempPath("empty.ot"),
                            &error))
      << error;
  std::unique_ptr<octomap::AbstractOcTree> tree(octomap::AbstractOcTree::read(TempPath("empty.ot")));
  ASSERT_NE(tree, nullptr);
  EXPECT_EQ(tree->size(), 0u);
}

TEST(CloudWriterTest, OctoMapsHoldOneOccupiedLeafPerVoxel) {
  const double res = 0.1;
  cloud::ColorCloud cloud;
  auto add = [&cloud](float x, float y, float z, uint8_t r, uint8_t g, uint8_t b) {
    cloud::ColorPoint p(r, g, b);
    p.x = x;
    p.y = y;
    p.z = z;
    cloud.push_back(p);
  };
  // Four separated voxels; the first holds three points whose colours average to (100, 50, 0).
  add(0.05f, 0.05f, 0.05f, 150, 0, 0);
  add(0.02f, 0.08f, 0.01f, 50, 150, 0);
  add(0.09f, 0.01f, 0.03f, 100, 0, 0);
  add(0.55f, 0.05f, 0.05f, 0, 0, 255);
  add(-0.35f, 1.05f, 0.25f, 0, 255, 0);
  add(0.05f, -0.75f, 1.45f, 9, 9, 9);
  const std::string bt = TempPath("map.bt");
  const std::string ot = TempPath("map.ot");
  std::string error;
  ASSERT_TRUE(WriteOctoMaps(cloud, res, bt, ot, &error)) << error;

  octomap::OcTree tree(res);
  ASSERT_TRUE(tree.readBinary(bt));
  EXPECT_DOUBLE_EQ(tree.getResolution(), res);
  int occupied = 0;
  for (auto it = tree.begin_leafs(); it != tree.end_leafs(); ++it) {
    occupied += tree.isNodeOccupied(*it) ? 1 : 0;
  }
  EXPECT_EQ(occupied, 4);
  ASSERT_NE(tree.search(0.55, 0.05, 0.05), nullptr);
  EXPECT_TRUE(tree.isNodeOccupied(tree.search(0.55, 0.05, 0.05)));
  EXPECT_EQ(tree.search(0.25, 0.05, 0.05), nullptr);  // Unknown, not free.

  std::unique_ptr<octomap::AbstractOcTree> abstract(octomap::AbstractOcTree::read(ot));
  auto* color_tree = dynamic_cast<octomap::ColorOcTree*>(abstract.get());
  ASSERT_NE(color_tree, nullptr);
  int color_occupied = 0;
  for (auto it = color_tree->begin_leafs(); it != color_tree->end_leafs(); ++it) {
    color_occupied += color_tree->isNodeOccupied(*it) ? 1 : 0;
  }
  EXPECT_EQ(color_occupied, 4);
  const octomap::ColorOcTreeNode* node = color_tree->search(0.05, 0.05, 0.05);
  ASSERT_NE(node, nullptr);
  EXPECT_EQ(node->getColor(), octomap::ColorOcTreeNode::Color(100, 50, 0));
}

TEST(CloudWriterTest, UnwritableOrMissingPathsReportTheirPath) {
  const std::string bad = "/nonexistent_fusemap_dir/cloud.ply";
  std::string error;
  EXPECT_FALSE(WriteCloudPly(bad, SmallCloud(), &error));
  EXPECT_NE(error.find(bad), std::string::npos) << error;
  error.clear();
  EXPECT_FALSE(WriteCloudPcd("/nonexistent_fusemap_dir/cloud.pcd", SmallCloud(), &error));
  EXPECT_NE(error.find("/nonexistent_fusemap_dir/cloud.pcd"), std::string::npos) << error;
  error.clear();
  EXPECT_FALSE(WriteOctoMaps(SmallCloud(), 0.05, "/nonexistent_fusemap_dir/o.bt", "", &error));
  EXPECT_NE(error.find("/nonexistent_fusemap_dir/o.bt"), std::string::npos) << error;
  error.clear();
  cloud::ColorCloud read;
  EXPECT_FALSE(ReadCloudPly("/nonexistent_fusemap_dir/in.ply", &read, &error));
  EXPECT_NE(error.find("/nonexistent_fusemap_dir/in.ply"), std::string::npos) << error;
}

}  // namespace
}  // namespace io
}  // namespace fusemap
