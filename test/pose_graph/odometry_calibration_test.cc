#include "fusemap/pose_graph/odometry_calibration.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "fusemap/common/math.h"

namespace fusemap {
namespace pose_graph {
namespace {

// Ground-truth increments of a robot that drives, turns on the spot and drives curves
// (both turn directions, forward only), sampled at 10 Hz for `seconds`.
std::vector<common::Rigid2d> TrueIncrements(double seconds) {
  std::vector<common::Rigid2d> increments;
  const int n = static_cast<int>(seconds * 10.0);
  for (int k = 0; k < n; ++k) {
    const double t = 0.1 * k;
    const int phase = static_cast<int>(t / 4.0) % 4;
    const double v_mps = phase == 1 ? 0.0 : 0.4;
    const double w_radps = phase == 1 ? 0.8 : (phase == 3 ? -0.25 : 0.1 * std::sin(t));
    increments.emplace_back(0.1 * v_mps, 0.0, 0.1 * w_radps);
  }
  return increments;
}

// Raw odometry integrating `raw` increments; the truth is those increments after `truth_from_raw`.
struct Scenario {
  std::vector<sensor::OdometryData> odometry;
  std::vector<MapBuilder2D::TimedPose2d> nodes;  // every `node_every`-th sample, in a map frame
};

Scenario MakeScenario(const OdometryCalibration& truth_from_raw, double seconds, int node_every) {
  Scenario s;
  const common::Rigid2d T_map_odom(5.0, -2.0, 0.4);
  common::Rigid2d raw_pose(1.0, 1.0, -0.3);
  s.odometry.push_back({0.0, raw_pose});
  const auto increments = TrueIncrements(seconds);
  for (size_t k = 0; k < increments.size(); ++k) {
    raw_pose = raw_pose * increments[k];
    s.odometry.push_back({0.1 * (k + 1), raw_pose});
  }
  const auto truth = ApplyOdometryCalibration(truth_from_raw, s.odometry);
  for (size_t k = 0; k < truth.size(); k += node_every) {
    s.nodes.push_back({truth[k].stamp_s, T_map_odom * truth[k].pose});
  }
  return s;
}

TEST(OdometryCalibrationTest, IdentityLeavesOdometryUnchanged) {
  const Scenario s = MakeScenario(OdometryCalibration(), 20.0, 30);
  const auto out = ApplyOdometryCalibration(OdometryCalibration(), s.odometry);
  ASSERT_EQ(out.size(), s.odometry.size());
  for (size_t i = 0; i < out.size(); ++i) {
    EXPECT_EQ(out[i].stamp_s, s.odometry[i].stamp_s);
    EXPECT_EQ(out[i].pose.x(), s.odometry[i].pose.x());
    EXPECT_EQ(out[i].pose.angle_rad(), s.odometry[i].pose.angle_rad());
  }
}

TEST(OdometryCalibrationTest, CalibrateIncrementFollowsTheModel) {
  OdometryCalibration c;
  c.translation_scale = 0.9;
  c.rotation_scale = 1.1;
  c.heading_drift_rad_per_m = 0.05;
  // 1 m forward while turning 0.2 rad: heading 1.1 * 0.2 + 0.05 * 1; the extra 0.07 rad turns
  // the chord by half of it; length scaled by 0.9.
  const common::Rigid2d out = CalibrateIncrement(c, common::Rigid2d(1.0, 0.0, 0.2));
  EXPECT_NEAR(out.angle_rad(), 0.27, 1e-12);
  EXPECT_NEAR(out.x(), 0.9 * std::cos(0.035), 1e-12);
  EXPECT_NEAR(out.y(), 0.9 * std::sin(0.035), 1e-12);
  // Backing up bends the other way; turning on the spot has no drift.
  EXPECT_NEAR(CalibrateIncrement(c, common::Rigid2d(-1.0, 0.0, 0.0)).angle_rad(), -0.05, 1e-12);
  EXPECT_NEAR(CalibrateIncrement(c, common::Rigid2d(0.0, 0.0, -0.5)).angle_rad(), -0.55, 1e-12);
}

OdometryCalibration FitWithDefaults(const Scenario& s) {
  OdometryCalibration fitted;
  std::string reason;
  EXPECT_TRUE(FitOdometryCalibration(s.nodes, s.odometry, OdometryCalibrationOptions(), &fitted,
                                     &reason))
      << reason;
  return fitted;
}

TEST(OdometryCalibrationTest, RecoversSystematicErrorsFromNodeMotion) {
  OdometryCalibration truth;
  truth.translation_scale = 0.95;
  truth.rotation_scale = 0.97;
  truth.heading_drift_rad_per_m = 0.057;  // 3.3 deg/m, as fitted on the Intel log
  const Scenario s = MakeScenario(truth, 300.0, 30);
  const OdometryCalibration fitted = FitWithDefaults(s);
  // The model is exact here; the small residue is from the linear translation step.
  EXPECT_NEAR(fitted.rotation_scale, truth.rotation_scale, 1e-6);
  EXPECT_NEAR(fitted.heading_drift_rad_per_m, truth.heading_drift_rad_per_m, 1e-6);
  EXPECT_NEAR(fitted.translation_scale, truth.translation_scale, 1e-6);

  // Densifying with the calibrated odometry then reproduces the truth between nodes, which
  // the raw odometry does not.
  const auto truth_odometry = ApplyOdometryCalibration(truth, s.odometry);
  const auto raw = DensifyWithOdometry(s.nodes, s.odometry);
  const auto calibrated = DensifyWithOdometry(s.nodes, ApplyOdometryCalibration(fitted, s.odometry));
  ASSERT_EQ(raw.size(), calibrated.size());
  double raw_max_m = 0.0, calibrated_max_m = 0.0;
  const common::Rigid2d T_map_odom = s.nodes.front().pose * s.odometry.front().pose.inverse();
  for (size_t i = 0; i < raw.size(); ++i) {
    const common::Rigid2d expected = T_map_odom * truth_odometry[i].pose;
    raw_max_m = std::max(raw_max_m, (raw[i].pose.translation() - expected.translation()).norm());
    calibrated_max_m = std::max(
        calibrated_max_m, (calibrated[i].pose.translation() - expected.translation()).norm());
  }
  EXPECT_GT(raw_max_m, 0.01);
  EXPECT_LT(calibrated_max_m, 1e-6);
}

TEST(OdometryCalibrationTest, RobustToNoiseAndAJumpInTheGraph) {
  OdometryCalibration truth;
  truth.translation_scale = 1.04;
  truth.rotation_scale = 0.98;
  truth.heading_drift_rad_per_m = -0.02;
  Scenario s = MakeScenario(truth, 400.0, 30);
  std::mt19937 rng(7);
  std::normal_distribution<double> xy_m(0.0, 0.005), angle_rad(0.0, 0.002);
  for (auto& node : s.nodes) {
    node.pose = node.pose * common::Rigid2d(xy_m(rng), xy_m(rng), angle_rad(rng));
  }
  // A loop closure that moved one node far: one bad interval on each side.
  s.nodes[40].pose = s.nodes[40].pose * common::Rigid2d(0.5, -0.3, 0.3);
  const OdometryCalibration fitted = FitWithDefaults(s);
  // Noise of 2 mrad per node over ~130 intervals of 0.3-2.4 rad / 1.2 m: a few 1e-3.
  EXPECT_NEAR(fitted.rotation_scale, truth.rotation_scale, 3e-3);
  EXPECT_NEAR(fitted.heading_drift_rad_per_m, truth.heading_drift_rad_per_m, 3e-3);
  EXPECT_NEAR(fitted.translation_scale, truth.translation_scale, 5e-3);
}

TEST(OdometryCalibrationTest, PerfectOdometryFitsIdentity) {
  const Scenario s = MakeScenario(OdometryCalibration(), 200.0, 25);
  const OdometryCalibration fitted = FitWithDefaults(s);
  EXPECT_NEAR(fitted.rotation_scale, 1.0, 1e-9);
  EXPECT_NEAR(fitted.heading_drift_rad_per_m, 0.0, 1e-9);
  EXPECT_NEAR(fitted.translation_scale, 1.0, 1e-9);
}

TEST(OdometryCalibrationTest, RefusesWhenTooLittleDataOrOutOfBounds) {
  OdometryCalibration truth;
  truth.rotation_scale = 0.9;
  // 20 s: 6 intervals, too few.
  const Scenario short_run = MakeScenario(truth, 20.0, 30);
  OdometryCalibration fitted;
  fitted.rotation_scale = 2.0;
  std::string reason;
  EXPECT_FALSE(FitOdometryCalibration(short_run.nodes, short_run.odometry,
                                      OdometryCalibrationOptions(), &fitted, &reason));
  EXPECT_TRUE(fitted.IsIdentity());
  EXPECT_NE(reason.find("too little motion"), std::string::npos) << reason;

  // Odometry 40 % off: not a wheel error the model is meant for.
  truth.rotation_scale = 1.4;
  const Scenario wrong = MakeScenario(truth, 300.0, 30);
  reason.clear();
  EXPECT_FALSE(FitOdometryCalibration(wrong.nodes, wrong.odometry, OdometryCalibrationOptions(),
                                      &fitted, &reason));
  EXPECT_TRUE(fitted.IsIdentity());
  EXPECT_NE(reason.find("out of bounds"), std::string::npos) << reason;
}

TEST(OdometryCalibrationTest, OptionsValidation) {
  std::string error;
  EXPECT_TRUE(OdometryCalibrationOptions().IsValid(&error));
  OdometryCalibrationOptions bad;
  bad.max_scale_deviation = 1.5;
  EXPECT_FALSE(bad.IsValid(&error));
  EXPECT_NE(error.find("max_scale_deviation"), std::string::npos);
}

}  // namespace
}  // namespace pose_graph
}  // namespace fusemap
