#include "fusemap/sensor/range_data_builder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace fusemap {
namespace sensor {
namespace {

constexpr float kTol = 1e-5f;

// Four beams at 0, 90, 180, 270 degrees.
LaserScan FourBeamScan(float r0, float r1, float r2, float r3) {
  LaserScan scan;
  scan.angle_min_rad = 0.f;
  scan.angle_increment_rad = static_cast<float>(M_PI / 2);
  scan.range_min_m = 0.1f;
  scan.range_max_m = 20.f;
  scan.ranges_m = {r0, r1, r2, r3};
  return scan;
}

TEST(RangeDataFromScanTest, ReturnsLieAlongBeams) {
  const RangeData data = RangeDataFromScan(FourBeamScan(1.f, 2.f, 3.f, 4.f), RangeGateOptions());
  ASSERT_EQ(data.returns.size(), 4u);
  EXPECT_TRUE(data.misses.empty());
  EXPECT_NEAR(data.origin.norm(), 0.f, kTol);
  EXPECT_NEAR(data.returns[0].x(), 1.f, kTol);
  EXPECT_NEAR(data.returns[0].y(), 0.f, kTol);
  EXPECT_NEAR(data.returns[1].y(), 2.f, kTol);
  EXPECT_NEAR(data.returns[2].x(), -3.f, kTol);
  EXPECT_NEAR(data.returns[3].y(), -4.f, kTol);
}

TEST(RangeDataFromScanTest, GateAndSensorLimitsSelectReturns) {
  RangeGateOptions options;
  options.min_range_m = 0.5f;
  options.max_range_m = 10.f;
  options.missing_data_ray_length_m = 3.f;
  // 0.05: below sensor min (dropped); 0.3: below gate min (dropped); 0.5: on the gate min
  // (kept, interval closed below); 10: on the gate max (interval open above -> miss).
  const RangeData data = RangeDataFromScan(FourBeamScan(0.05f, 0.3f, 0.5f, 10.f), options);
  ASSERT_EQ(data.returns.size(), 1u);
  EXPECT_NEAR(data.returns[0].x(), -0.5f, kTol);
  ASSERT_EQ(data.misses.size(), 1u);
  EXPECT_NEAR(data.misses[0].y(), -3.f, kTol);
  EXPECT_NEAR(data.misses[0].norm(), 3.f, kTol);
}

TEST(RangeDataFromScanTest, NoReturnBeamsBecomeMissesAtConfiguredLength) {
  RangeGateOptions options;
  options.missing_data_ray_length_m = 5.f;
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  // 20 is the sensor max (open interval: no return), then inf, NaN, and 25 beyond the max.
  const RangeData data = RangeDataFromScan(FourBeamScan(20.f, inf, nan, 25.f), options);
  EXPECT_TRUE(data.returns.empty());
  ASSERT_EQ(data.misses.size(), 4u);
  for (const auto& miss : data.misses) EXPECT_NEAR(miss.norm(), 5.f, kTol);
  EXPECT_NEAR(data.misses[1].y(), 5.f, kTol);
  EXPECT_NEAR(data.misses[2].x(), -5.f, kTol);
}

TEST(RangeDataFromScanTest, MissBeyondGateIsNotLongerThanTheMeasuredRange) {
  RangeGateOptions options;
  options.max_range_m = 4.f;
  options.missing_data_ray_length_m = 8.f;
  const RangeData data = RangeDataFromScan(FourBeamScan(6.f, 1.f, 1.f, 1.f), options);
  EXPECT_EQ(data.returns.size(), 3u);
  ASSERT_EQ(data.misses.size(), 1u);
  EXPECT_NEAR(data.misses[0].x(), 6.f, kTol);
}

TEST(RangeDataFromScanTest, MissesCanBeDisabled) {
  RangeGateOptions options;
  options.insert_misses = false;
  const RangeData data =
      RangeDataFromScan(FourBeamScan(1.f, std::numeric_limits<float>::infinity(), 2.f, 30.f),
                        options);
  EXPECT_EQ(data.returns.size(), 2u);
  EXPECT_TRUE(data.misses.empty());
}

TEST(RangeGateOptionsTest, ParseReadsKeysAndRejectsBadRanges) {
  std::string error;
  auto reader = common::ConfigReader::FromString(
      "min_range_m: 0.2\nmax_range_m: 12\nmissing_data_ray_length_m: 4\ninsert_misses: false\n",
      "gate.yaml", &error);
  ASSERT_NE(reader, nullptr) << error;
  const RangeGateOptions options = ParseRangeGateOptions(*reader);
  EXPECT_TRUE(reader->Finish(&error)) << error;
  EXPECT_FLOAT_EQ(options.min_range_m, 0.2f);
  EXPECT_FLOAT_EQ(options.max_range_m, 12.f);
  EXPECT_FLOAT_EQ(options.missing_data_ray_length_m, 4.f);
  EXPECT_FALSE(options.insert_misses);

  auto bad = common::ConfigReader::FromString("min_range_m: 5\nmax_range_m: 1\n", "bad.yaml",
                                              &error);
  ASSERT_NE(bad, nullptr);
  ParseRangeGateOptions(*bad);
  EXPECT_FALSE(bad->Finish(&error));
}

}  // namespace
}  // namespace sensor
}  // namespace fusemap
