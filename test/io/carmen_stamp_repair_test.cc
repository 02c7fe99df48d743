#include "carmen_stamp_repair.h"

#include <gtest/gtest.h>

#include <vector>

namespace fusemap {
namespace io {
namespace {

TEST(PrintedStampResolutionTest, SixSignificantDigitsAsGMappingPrints) {
  EXPECT_DOUBLE_EQ(PrintedStampResolution("1401.34"), 0.01);
  EXPECT_DOUBLE_EQ(PrintedStampResolution("12.3457"), 1e-4);
  EXPECT_DOUBLE_EQ(PrintedStampResolution("999.999"), 1e-3);
  // Trailing zeros are not printed: "1401.3" is 1401.30 to 0.01 and "1400" is 1400.00.
  EXPECT_DOUBLE_EQ(PrintedStampResolution("1401.3"), 0.01);
  EXPECT_DOUBLE_EQ(PrintedStampResolution("1400"), 0.01);
  EXPECT_DOUBLE_EQ(PrintedStampResolution("9.76053e+08"), 1000.0);
}

TEST(PrintedStampResolutionTest, LongerTextResolvesItsLastDecimal) {
  EXPECT_DOUBLE_EQ(PrintedStampResolution("976052857.337284"), 1e-6);
  EXPECT_DOUBLE_EQ(PrintedStampResolution("1401.3456"), 1e-4);
  EXPECT_DOUBLE_EQ(PrintedStampResolution("-1401.3456"), 1e-4);
}

TEST(PrintedStampResolutionTest, ZeroAndGarbageGiveZero) {
  EXPECT_EQ(PrintedStampResolution("0"), 0.0);
  EXPECT_EQ(PrintedStampResolution("0.000"), 0.0);
  EXPECT_EQ(PrintedStampResolution("abc"), 0.0);
  EXPECT_EQ(PrintedStampResolution("12x4"), 0.0);
  EXPECT_EQ(PrintedStampResolution(""), 0.0);
}

TEST(SpreadOverRoundingTest, InstantsSpreadEvenlyOverTheInterval) {
  // Three ODOM lines and a scan taken with the third: three instants in [1401.335, 1401.345).
  const std::vector<double> stamps =
      SpreadOverRounding(1401.34, 0.01, {true, true, true, false});
  ASSERT_EQ(stamps.size(), 4u);
  const double step = 0.01 / 3.0;
  EXPECT_NEAR(stamps[0], 1401.335 + 0.5 * step, 1e-9);
  EXPECT_NEAR(stamps[1], 1401.335 + 1.5 * step, 1e-9);
  EXPECT_NEAR(stamps[2], 1401.335 + 2.5 * step, 1e-9);
  EXPECT_DOUBLE_EQ(stamps[3], stamps[2]);
  // The centre of the spread is the printed value.
  EXPECT_NEAR(stamps[1], 1401.34, 1e-9);
}

TEST(SpreadOverRoundingTest, OneInstantKeepsThePrintedStamp) {
  EXPECT_EQ(SpreadOverRounding(1401.34, 0.01, {true, false}), std::vector<double>(2, 1401.34));
  EXPECT_EQ(SpreadOverRounding(5.0, 0.01, {true}), std::vector<double>(1, 5.0));
  EXPECT_TRUE(SpreadOverRounding(5.0, 0.01, {}).empty());
  // The first record always starts an instant.
  const std::vector<double> stamps = SpreadOverRounding(2.0, 0.1, {false, true});
  EXPECT_NEAR(stamps[0], 1.975, 1e-12);
  EXPECT_NEAR(stamps[1], 2.025, 1e-12);
}

TEST(SpreadOverRoundingTest, ZeroResolutionLeavesStampsAlone) {
  EXPECT_EQ(SpreadOverRounding(3.0, 0.0, {true, true}), std::vector<double>(2, 3.0));
}

}  // namespace
}  // namespace io
}  // namespace fusemap
