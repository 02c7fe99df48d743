#include "fusemap/cloud/free_column_filter.h"

#include <gtest/gtest.h>

namespace fusemap {
namespace cloud {
namespace {

ColorPoint Point(float x, float y, float z) {
  ColorPoint p;
  p.x = x, p.y = y, p.z = z;
  return p;
}

TEST(FreeColumnFilterTest, RemovesOnlyRarelySeenBodyHeightPointsInFreeColumns) {
  // The laser map is free for x < 5 and occupied (a wall) from x = 5 on.
  const auto is_free = [](double x_m, double /*y_m*/) { return x_m < 5.0; };
  ColorCloud cloud;
  std::vector<uint16_t> hits;
  cloud.push_back(Point(1, 0, 1.0)), hits.push_back(1);   // person, seen once: removed
  cloud.push_back(Point(1, 0, 0.02)), hits.push_back(1);  // floor under them: kept
  cloud.push_back(Point(2, 0, 0.8)), hits.push_back(30);  // table top seen often: kept
  cloud.push_back(Point(6, 0, 1.0)), hits.push_back(1);   // wall: kept
  cloud.push_back(Point(1, 0, 2.8)), hits.push_back(1);   // ceiling: kept
  ColorCloud removed;
  const size_t moved = RemoveInFreeColumns(is_free, FreeColumnFilterOptions(), hits, &cloud, &removed);
  EXPECT_EQ(moved, 1u);
  ASSERT_EQ(removed.size(), 1u);
  EXPECT_FLOAT_EQ(removed[0].z, 1.0f);
  EXPECT_EQ(cloud.size(), 4u);
}

TEST(FreeColumnFilterTest, DisabledKeepsEverythingAndOptionsAreChecked) {
  ColorCloud cloud;
  cloud.push_back(Point(1, 0, 1.0));
  std::vector<uint16_t> hits = {1};
  ColorCloud removed;
  FreeColumnFilterOptions options;
  options.enabled = false;
  EXPECT_EQ(RemoveInFreeColumns([](double, double) { return true; }, options, hits, &cloud, &removed), 0u);
  EXPECT_EQ(cloud.size(), 1u);
  std::string error;
  options.min_z_m = 3.0;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("min_z_m"), std::string::npos);
}

}  // namespace
}  // namespace cloud
}  // namespace fusemap
