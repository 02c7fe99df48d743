#include "fusemap/eval/absolute_trajectory_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace fusemap {
namespace eval {
namespace {

// A non-degenerate 3D path (not collinear, not planar) at 20 Hz.
Trajectory Path() {
  Trajectory t;
  for (int i = 0; i < 400; ++i) {
    const double s = 0.05 * i;
    const Eigen::Quaterniond q(Eigen::AngleAxisd(0.3 * s, Eigen::Vector3d::UnitZ()));
    t.push_back(TimedPose3d{
        s, common::Rigid3d(
               Eigen::Vector3d(3.0 * std::cos(0.3 * s), 2.0 * std::sin(0.5 * s), 0.2 * std::sin(s)),
               q)});
  }
  return t;
}

Trajectory Transformed(const Trajectory& in, const common::Rigid3d& T) {
  Trajectory out = in;
  for (TimedPose3d& p : out) p.pose = T * p.pose;
  return out;
}

TEST(AteTest, RigidlyMovedCopyIsZeroAfterAlignment) {
  const Trajectory gt = Path();
  const common::Rigid3d T_est_gt(
      Eigen::Vector3d(1.0, -2.0, 0.5),
      Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.2, 0.3, 1.0).normalized())));
  const Trajectory est = Transformed(gt, T_est_gt);
  const AteResult r = ComputeAte(gt, est, AteOptions());
  EXPECT_EQ(r.trans_m.count, 400);
  EXPECT_NEAR(r.trans_m.rmse, 0.0, 1e-9);
  EXPECT_NEAR(r.trans_m.max, 0.0, 1e-9);
  const common::Rigid3d residual = r.T_gt_est * T_est_gt;
  EXPECT_NEAR(residual.translation().norm(), 0.0, 1e-9);
  EXPECT_NEAR(residual.rotation().angularDistance(Eigen::Quaterniond::Identity()), 0.0, 1e-9);
  EXPECT_GT(r.unaligned_rmse_m, 1.0);
}

TEST(AteTest, PureTranslationWithoutAlignmentGivesOffset) {
  const Trajectory gt = Path();
  const Trajectory est = Transformed(
      gt, common::Rigid3d(Eigen::Vector3d(0.3, 0.4, 0.0), Eigen::Quaterniond::Identity()));
  AteOptions options;
  options.align = false;
  const AteResult r = ComputeAte(gt, est, options);
  EXPECT_NEAR(r.trans_m.rmse, 0.5, 1e-12);
  EXPECT_NEAR(r.trans_m.mean, 0.5, 1e-12);
  EXPECT_NEAR(r.trans_m.median, 0.5, 1e-12);
  EXPECT_NEAR(r.unaligned_rmse_m, 0.5, 1e-12);
  EXPECT_NEAR(ComputeAte(gt, est, AteOptions()).trans_m.rmse, 0.0, 1e-9);
}

TEST(AteTest, IsotropicNoiseGivesItsRms) {
  // Gaussian noise sigma per axis: expected ATE RMSE sqrt(3) sigma; alignment absorbs little.
  const Trajectory gt = Path();
  Trajectory est = gt;
  std::mt19937 rng(42);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (TimedPose3d& p : est) {
    p.pose =
        common::Rigid3d(p.pose.translation() + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)),
                        p.pose.rotation());
  }
  const AteResult r = ComputeAte(gt, est, AteOptions());
  EXPECT_NEAR(r.trans_m.rmse, std::sqrt(3.0) * 0.01, 0.0015);
  EXPECT_LE(r.trans_m.rmse, r.unaligned_rmse_m);  // Alignment can only reduce the RMSE.
}

TEST(AteTest, AssociationToleranceAndEmptyResult) {
  const Trajectory gt = Path();
  Trajectory est = gt;
  for (TimedPose3d& p : est)
    p.stamp_s += 0.024;  // Samples are 0.05 s apart: nearest gt is 0.024 s away.
  EXPECT_EQ(ComputeAte(gt, est, AteOptions()).trans_m.count, 0);
  AteOptions loose;
  loose.max_time_diff_s = 0.03;
  EXPECT_EQ(ComputeAte(gt, est, loose).trans_m.count, 400);
}

// A planar path (z = 0, yaw only) that is not symmetric about any line.
Trajectory PlanarPath() {
  Trajectory t;
  for (int i = 0; i < 200; ++i) {
    const double s = 0.1 * i;
    const double yaw_rad = 0.4 * s;
    t.push_back(TimedPose3d{
        s, common::Rigid3d(Eigen::Vector3d(s + std::cos(yaw_rad), 0.3 * s * s + std::sin(yaw_rad), 0.0),
                           Eigen::Quaterniond(Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ())))});
  }
  return t;
}

TEST(AteTest, PlanarAlignmentRecoversAMotionInThePlane) {
  const Trajectory gt = PlanarPath();
  const common::Rigid3d T_est_gt =
      common::Rigid3d::FromRigid2d(common::Rigid2d(4.0, -3.0, 2.5));
  AteOptions options;
  options.planar = true;
  const AteResult r = ComputeAte(gt, Transformed(gt, T_est_gt), options);
  EXPECT_EQ(r.trans_m.count, 200);
  EXPECT_NEAR(r.trans_m.rmse, 0.0, 1e-9);
  const common::Rigid3d residual = r.T_gt_est * T_est_gt;
  EXPECT_NEAR(residual.translation().norm(), 0.0, 1e-9);
  EXPECT_NEAR(residual.rotation().angularDistance(Eigen::Quaterniond::Identity()), 0.0, 1e-9);
}

TEST(AteTest, PlanarAlignmentDoesNotMirrorThePlane) {
  // The mirror image (y -> -y) of a path is a half turn about the x axis in 3D, so the SE(3)
  // fit makes it perfect; no motion in the plane does.
  const Trajectory gt = PlanarPath();
  Trajectory mirrored = gt;
  for (TimedPose3d& p : mirrored) {
    const Eigen::Vector3d t = p.pose.translation();
    p.pose = common::Rigid3d(Eigen::Vector3d(t.x(), -t.y(), 0.0), p.pose.rotation().conjugate());
  }
  EXPECT_NEAR(ComputeAte(gt, mirrored, AteOptions()).trans_m.rmse, 0.0, 1e-6);
  AteOptions planar;
  planar.planar = true;
  const AteResult r = ComputeAte(gt, mirrored, planar);
  EXPECT_GT(r.trans_m.rmse, 1.0);
  EXPECT_NEAR(r.T_gt_est.translation().z(), 0.0, 1e-12);
}

TEST(AteTest, SimilarityAlignmentRecoversAScaleTheRigidOneLeavesAsError) {
  // The estimate is the ground truth 1 % larger (about a point off the path), then moved in
  // the plane: a map that came out too large.
  const Trajectory gt = PlanarPath();
  const common::Rigid3d T_est_gt = common::Rigid3d::FromRigid2d(common::Rigid2d(4.0, -3.0, 2.5));
  Trajectory est = gt;
  const Eigen::Vector3d centre(1.0, 2.0, 0.0);
  for (TimedPose3d& p : est) {
    p.pose = T_est_gt *
             common::Rigid3d(centre + 1.01 * (p.pose.translation() - centre), p.pose.rotation());
  }
  AteOptions rigid;
  rigid.planar = true;
  const AteResult r_rigid = ComputeAte(gt, est, rigid);
  EXPECT_GT(r_rigid.trans_m.rmse, 0.01);
  EXPECT_DOUBLE_EQ(r_rigid.scale, 1.0);
  AteOptions similarity = rigid;
  similarity.scale = true;
  const AteResult r = ComputeAte(gt, est, similarity);
  EXPECT_EQ(r.trans_m.count, 200);
  EXPECT_NEAR(r.trans_m.rmse, 0.0, 1e-9);
  EXPECT_NEAR(r.scale, 1.0 / 1.01, 1e-12);
  EXPECT_NEAR(r.T_gt_est.translation().z(), 0.0, 1e-12);
}

TEST(AteTest, InterpolatesAnEstimateSampledAtOtherStamps) {
  // Ground truth at 1 Hz, the estimate (a straight line at constant speed) at 10 Hz, offset by
  // 0.04 s: nearest association within 0.02 s finds nothing, interpolation is exact.
  Trajectory gt, est;
  for (int i = 1; i < 10; ++i) {
    gt.push_back({1.0 * i, common::Rigid3d::FromRigid2d(common::Rigid2d(2.0 * i, 1.0, 0.0))});
  }
  for (int i = 0; i < 100; ++i) {
    const double s = 0.1 * i + 0.04;
    est.push_back({s, common::Rigid3d::FromRigid2d(common::Rigid2d(2.0 * s + 0.5, 1.0, 0.0))});
  }
  AteOptions options;
  options.align = false;
  EXPECT_EQ(ComputeAte(gt, est, options).trans_m.count, 0);
  options.interpolate_max_gap_s = 0.1;
  const AteResult r = ComputeAte(gt, est, options);
  EXPECT_EQ(r.trans_m.count, 9);
  EXPECT_NEAR(r.trans_m.max, 0.5, 1e-9);
  EXPECT_NEAR(r.trans_m.rmse, 0.5, 1e-9);
}

TEST(AteTest, OptionsValidation) {
  std::string error;
  AteOptions options;
  EXPECT_TRUE(options.IsValid(&error));
  options.max_time_diff_s = -1.0;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("max_time_diff_s"), std::string::npos);
  options = AteOptions();
  options.interpolate_max_gap_s = -0.1;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("interpolate_max_gap_s"), std::string::npos);
  options = AteOptions();
  options.scale = true;  // a scale only with the planar alignment
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("scale"), std::string::npos);
  options.planar = true;
  EXPECT_TRUE(options.IsValid(&error)) << error;
  options.align = false;
  EXPECT_FALSE(options.IsValid(&error));
}

TEST(AteTest, ParseOptions) {
  std::string error;
  auto reader =
      common::ConfigReader::FromString("max_time_diff_s: 0.1\nalign: false\n", "test", &error);
  ASSERT_NE(reader, nullptr) << error;
  const AteOptions options = ParseAteOptions(*reader);
  EXPECT_TRUE(reader->Finish(&error)) << error;
  EXPECT_DOUBLE_EQ(options.max_time_diff_s, 0.1);
  EXPECT_FALSE(options.align);

  auto bad = common::ConfigReader::FromString("align: true\ninterpolate_max_gap_s: -1\n", "test",
                                              &error);
  ASSERT_NE(bad, nullptr) << error;
  ParseAteOptions(*bad);
  EXPECT_FALSE(bad->Finish(&error));
  EXPECT_EQ(error, "test:2: key 'interpolate_max_gap_s': must be finite and >= 0");
}

}  // namespace
}  // namespace eval
}  // namespace fusemap
