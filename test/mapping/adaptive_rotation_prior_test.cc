#include "fusemap/mapping/adaptive_rotation_prior.h"

#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "fusemap/common/math.h"

namespace fusemap {
namespace mapping {
namespace {

constexpr double kConfigured = 0.1;

double Deg(double degrees) { return common::DegToRad(degrees); }

AdaptiveRotationPriorOptions Options() {
  AdaptiveRotationPriorOptions options;
  options.weight_deg = 0.5;
  options.min_weight = 0.1;
  options.max_weight = 2.0;
  options.window_scans = 5;
  options.min_scans = 3;
  return options;
}

TEST(AdaptiveRotationPriorTest, ConfiguredWeightUntilEnoughCorrections) {
  AdaptiveRotationPrior prior(Options());
  EXPECT_EQ(prior.Weight(kConfigured), kConfigured);
  prior.AddCorrection(Deg(0.5));
  prior.AddCorrection(Deg(0.5));
  EXPECT_EQ(prior.Weight(kConfigured), kConfigured);
  prior.AddCorrection(Deg(0.5));
  EXPECT_NEAR(prior.Weight(kConfigured), 1.0, 1e-9);  // 0.5 / 0.5 degrees
}

TEST(AdaptiveRotationPriorTest, GoodOdometryHoldsBadOdometryLetsScansDecide) {
  AdaptiveRotationPrior good(Options());
  AdaptiveRotationPrior bad(Options());
  for (int i = 0; i < 5; ++i) {
    // Signs alternate: only the size of a correction counts.
    good.AddCorrection((i % 2 ? 1 : -1) * Deg(0.4));
    bad.AddCorrection((i % 2 ? 1 : -1) * Deg(4.0));
  }
  EXPECT_NEAR(good.Weight(kConfigured), 1.25, 1e-9);
  EXPECT_NEAR(bad.Weight(kConfigured), 0.125, 1e-9);
  // Beyond the clamps.
  AdaptiveRotationPrior perfect(Options());
  AdaptiveRotationPrior awful(Options());
  for (int i = 0; i < 5; ++i) {
    perfect.AddCorrection(0.0);
    awful.AddCorrection(Deg(30.0));
  }
  EXPECT_EQ(perfect.Weight(kConfigured), 2.0);
  EXPECT_EQ(awful.Weight(kConfigured), 0.1);
}

TEST(AdaptiveRotationPriorTest, MedianOfTheLastWindowOnly) {
  AdaptiveRotationPrior prior(Options());
  // One wild correction among small ones moves the median not at all.
  for (const double d : {0.5, 0.5, 20.0, 0.5, 0.5}) prior.AddCorrection(Deg(d));
  EXPECT_NEAR(prior.Weight(kConfigured), 1.0, 1e-9);
  // Five larger ones push the older ones out of the window.
  for (int i = 0; i < 5; ++i) prior.AddCorrection(Deg(2.5));
  EXPECT_NEAR(prior.Weight(kConfigured), 0.2, 1e-9);
  EXPECT_EQ(prior.corrections_rad().size(), 5u);
}

TEST(AdaptiveRotationPriorTest, AngleWrapsAndNonFiniteIgnored) {
  AdaptiveRotationPrior prior(Options());
  // 2 pi + 1 degree is a 1 degree correction.
  for (int i = 0; i < 3; ++i) prior.AddCorrection(2.0 * common::kPi + Deg(1.0));
  prior.AddCorrection(std::numeric_limits<double>::quiet_NaN());
  prior.AddCorrection(std::numeric_limits<double>::infinity());
  EXPECT_EQ(prior.corrections_rad().size(), 3u);
  EXPECT_NEAR(prior.Weight(kConfigured), 0.5, 1e-9);
}

TEST(AdaptiveRotationPriorTest, DisabledKeepsTheConfiguredWeight) {
  AdaptiveRotationPriorOptions options = Options();
  options.enabled = false;
  AdaptiveRotationPrior prior(options);
  for (int i = 0; i < 5; ++i) prior.AddCorrection(Deg(0.1));
  EXPECT_EQ(prior.Weight(kConfigured), kConfigured);
  EXPECT_TRUE(prior.corrections_rad().empty());
}

TEST(AdaptiveRotationPriorTest, RestoreGivesTheSameWeight) {
  AdaptiveRotationPrior prior(Options());
  for (const double d : {0.3, 1.0, 0.7, 2.0}) prior.AddCorrection(Deg(d));
  AdaptiveRotationPrior restored(Options());
  restored.Restore(prior.corrections_rad());
  EXPECT_EQ(restored.corrections_rad(), prior.corrections_rad());
  EXPECT_EQ(restored.Weight(kConfigured), prior.Weight(kConfigured));
}

TEST(AdaptiveRotationPriorTest, OptionsAreChecked) {
  std::string error;
  EXPECT_TRUE(Options().IsValid(&error)) << error;
  AdaptiveRotationPriorOptions options = Options();
  options.max_weight = 0.05;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("max_weight"), std::string::npos) << error;
  options = Options();
  options.min_scans = 6;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("min_scans"), std::string::npos) << error;
  options = Options();
  options.weight_deg = 0.0;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("weight_deg"), std::string::npos) << error;
}

}  // namespace
}  // namespace mapping
}  // namespace fusemap
