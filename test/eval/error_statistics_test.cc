#include "fusemap/eval/error_statistics.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fusemap {
namespace eval {
namespace {

TEST(ErrorStatisticsTest, KnownValues) {
  const ErrorStatistics s = ComputeErrorStatistics({4.0, 1.0, 3.0, 2.0});
  EXPECT_EQ(s.count, 4);
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(1.25));
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(7.5));
  EXPECT_DOUBLE_EQ(s.median, 2.5);
  EXPECT_DOUBLE_EQ(s.max, 4.0);
  EXPECT_DOUBLE_EQ(ComputeErrorStatistics({5.0, 1.0, 3.0}).median, 3.0);
}

TEST(ErrorStatisticsTest, EmptyIsAllZero) {
  const ErrorStatistics s = ComputeErrorStatistics({});
  EXPECT_EQ(s.count, 0);
  EXPECT_EQ(s.rmse, 0.0);
}

}  // namespace
}  // namespace eval
}  // namespace fusemap
