#include "fusemap/common/math.h"

#include <gtest/gtest.h>

#include <vector>

namespace fusemap {
namespace common {
namespace {

TEST(MathTest, PercentileNearestRank) {
  std::vector<double> values;
  for (int i = 100; i >= 1; --i) values.push_back(i);
  EXPECT_DOUBLE_EQ(Percentile(values, 0.5), 51.0);  // rank round(0.5 * 99) = 50 -> 51
  EXPECT_DOUBLE_EQ(Percentile(values, 0.99), 99.0);
  EXPECT_DOUBLE_EQ(Percentile(values, 1.0), 100.0);
  EXPECT_DOUBLE_EQ(Percentile({}, 0.5), 0.0);
  // An even count: the upper median, as local SLAM's heading prior and odometry calibration
  // take it.
  EXPECT_DOUBLE_EQ(Percentile({4.0, 1.0, 3.0, 2.0}, 0.5), 3.0);
  // The caller's values are left as they were.
  EXPECT_EQ(values.front(), 100.0);
}

TEST(MathTest, DegreesAndRadians) {
  EXPECT_DOUBLE_EQ(DegToRad(180.0), kPi);
  EXPECT_DOUBLE_EQ(RadToDeg(kPi / 2.0), 90.0);
}

}  // namespace
}  // namespace common
}  // namespace fusemap
