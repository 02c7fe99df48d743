#include "fusemap/mapping/motion_filter.h"

#include <gtest/gtest.h>

namespace fusemap {
namespace mapping {
namespace {

TEST(MotionFilterTest, DropsStandingStillUntilTimeOrMotionThreshold) {
  MotionFilterOptions options;
  options.max_time_s = 5.0;
  options.max_distance_m = 0.2;
  options.max_angle_rad = 0.1;
  MotionFilter filter(options);
  EXPECT_FALSE(filter.IsSimilar(0.0, common::Rigid2d(0, 0, 0)));
  EXPECT_TRUE(filter.IsSimilar(1.0, common::Rigid2d(0.1, 0, 0.05)));
  EXPECT_FALSE(filter.IsSimilar(2.0, common::Rigid2d(0.25, 0, 0)));
  EXPECT_FALSE(filter.IsSimilar(3.0, common::Rigid2d(0.25, 0, 0.2)));
  EXPECT_FALSE(filter.IsSimilar(8.5, common::Rigid2d(0.25, 0, 0.2)));
  EXPECT_EQ(filter.num_accepted(), 4);
  EXPECT_EQ(filter.num_total(), 5);
}

TEST(MotionFilterTest, ParseRejectsNegativeThresholds) {
  std::string error;
  auto reader = common::ConfigReader::FromString("max_distance_m: -1\n", "mf.yaml", &error);
  ASSERT_NE(reader, nullptr);
  ParseMotionFilterOptions(*reader);
  EXPECT_FALSE(reader->Finish(&error));
}

}  // namespace
}  // namespace mapping
}  // namespace fusemap
