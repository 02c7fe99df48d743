#include "fusemap/visual_loop/geometric_verifier.h"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "visual_loop/synthetic_views.h"

namespace fusemap {
namespace visual_loop {
namespace {

constexpr double kPlaneDepthM = 2.0;

struct Views {
  Keyframe a;
  Keyframe b;
};

Views MakeViews(const common::Rigid3d& T_a_b, bool depth_in_a, const cv::Mat& mask_b = cv::Mat()) {
  const sensor::PinholeIntrinsics in = testing::TestIntrinsics();
  const cv::Mat image_a = testing::RandomTexture(in.width, in.height, 7);
  cv::Mat image_b = testing::WarpToView(image_a, T_a_b, in, kPlaneDepthM);
  if (!mask_b.empty()) image_b.setTo(cv::Scalar(128), mask_b);
  const cv::Mat depth_a = depth_in_a ? cv::Mat(in.height, in.width, CV_32FC1, cv::Scalar(kPlaneDepthM))
                                     : cv::Mat();
  const OrbExtractor extractor{OrbOptions{}};
  return {MakeKeyframe(image_a, depth_a, in, extractor, nullptr, KeyframeOptions{}),
          MakeKeyframe(image_b, cv::Mat(), in, extractor, nullptr, KeyframeOptions{})};
}

TEST(GeometricVerifierTest, PnpRecoversTheKnownTransform) {
  const common::Rigid3d T_a_b = testing::PoseFromTranslationRpy(0.15, -0.05, 0.10, 0.03, -0.08, 0.05);
  const Views views = MakeViews(T_a_b, true);
  const VerificationResult result = VerifyKeyframes(views.a, views.b, VerificationOptions{});
  ASSERT_TRUE(result.verified) << result.reason;
  EXPECT_EQ(result.method, VerificationMethod::kPnp);
  EXPECT_TRUE(result.metric);
  EXPECT_GT(result.inliers, 200);
  EXPECT_LT((result.T_a_b.translation() - T_a_b.translation()).norm(), 0.005);
  EXPECT_LT(testing::AngleBetweenDeg(result.T_a_b, T_a_b), 0.1);
  // The covariance is a small, symmetric, positive definite 6x6 matrix.
  EXPECT_LT((result.covariance - result.covariance.transpose()).norm(), 1e-12);
  const Eigen::SelfAdjointEigenSolver<Matrix6d> eigen(result.covariance);
  EXPECT_GT(eigen.eigenvalues().minCoeff(), 0.0);
  EXPECT_LT(std::sqrt(result.covariance(0, 0)), 0.005);
}

TEST(GeometricVerifierTest, CountsTheMatchesAPoseExplains) {
  const common::Rigid3d T_a_b =
      testing::PoseFromTranslationRpy(0.15, -0.05, 0.10, 0.03, -0.08, 0.05);
  const Views views = MakeViews(T_a_b, true);
  const VerificationOptions options;
  const VerificationResult result = VerifyKeyframes(views.a, views.b, options);
  ASSERT_TRUE(result.verified) << result.reason;
  // The true pose explains what verification kept (within a few at the threshold's edge).
  const int at_truth = CountMatchesExplained(views.a, views.b, T_a_b, options);
  EXPECT_GE(at_truth, result.inliers - 5);
  EXPECT_LE(at_truth, result.matches);
  // 0.3 m sideways of it, almost none: 0.3 m at 2 m is ~80 px.
  const common::Rigid3d sideways =
      T_a_b * common::Rigid3d(Eigen::Vector3d(0.3, 0.0, 0.0), Eigen::Quaterniond::Identity());
  EXPECT_LT(CountMatchesExplained(views.a, views.b, sideways, options), result.inliers / 10);
  // Without depth in a there is nothing to project.
  EXPECT_EQ(CountMatchesExplained(views.b, views.a, T_a_b.inverse(), options), 0);
}

TEST(GeometricVerifierTest, EssentialMatrixRecoversRotationAndDirectionWithoutDepth) {
  // Two planes (left half near, right half far): a plane alone is ambiguous for the essential
  // matrix (two valid decompositions).
  const sensor::PinholeIntrinsics in = testing::TestIntrinsics();
  const common::Rigid3d T_a_b = testing::PoseFromTranslationRpy(0.3, 0.0, 0.05, 0.0, -0.1, 0.0);
  const cv::Mat image_a = testing::RandomTexture(in.width, in.height, 7);
  cv::Mat left_mask(in.height, in.width, CV_8UC1, cv::Scalar(0));
  left_mask(cv::Rect(0, 0, in.width / 2, in.height)).setTo(255);
  const cv::Mat near_b = testing::WarpToView(image_a, T_a_b, in, 1.5);
  const cv::Mat far_b = testing::WarpToView(image_a, T_a_b, in, 4.0);
  const cv::Mat near_mask_b = testing::WarpToView(left_mask, T_a_b, in, 1.5);
  cv::Mat image_b = far_b.clone();
  near_b.copyTo(image_b, near_mask_b > 200);
  const OrbExtractor extractor{OrbOptions{}};
  const Keyframe a = MakeKeyframe(image_a, cv::Mat(), in, extractor, nullptr, KeyframeOptions{});
  const Keyframe b = MakeKeyframe(image_b, cv::Mat(), in, extractor, nullptr, KeyframeOptions{});
  const VerificationResult result = VerifyKeyframes(a, b, VerificationOptions{});
  ASSERT_TRUE(result.verified) << result.reason;
  EXPECT_EQ(result.method, VerificationMethod::kEssential);
  EXPECT_FALSE(result.metric);
  EXPECT_LT(testing::AngleBetweenDeg(result.T_a_b, T_a_b), 1.0);
  EXPECT_GT(result.T_a_b.translation().normalized().dot(T_a_b.translation().normalized()), 0.98);
}

TEST(GeometricVerifierTest, FundamentalMatrixWithoutIntrinsicsGivesNoPose) {
  const common::Rigid3d T_a_b = testing::PoseFromTranslationRpy(0.3, 0.0, 0.05, 0.0, -0.1, 0.0);
  Views views = MakeViews(T_a_b, false);
  views.a.intrinsics = views.b.intrinsics = sensor::PinholeIntrinsics{};
  const VerificationResult result = VerifyKeyframes(views.a, views.b, VerificationOptions{});
  EXPECT_EQ(result.method, VerificationMethod::kFundamental);
  EXPECT_TRUE(result.verified) << result.reason;
  EXPECT_FALSE(result.has_pose);
}

TEST(GeometricVerifierTest, InliersInOneCornerAreRejectedForSpread) {
  const sensor::PinholeIntrinsics in = testing::TestIntrinsics();
  const common::Rigid3d T_a_b = testing::PoseFromTranslationRpy(0.05, 0.0, 0.0, 0.0, 0.0, 0.0);
  // Only the top-left corner of view b keeps its texture: a poster, not a place.
  cv::Mat mask(in.height, in.width, CV_8UC1, cv::Scalar(255));
  mask(cv::Rect(0, 0, in.width / 4, in.height / 3)).setTo(0);
  const Views views = MakeViews(T_a_b, true, mask);
  VerificationOptions options;
  options.min_inliers = 20;
  const VerificationResult result = VerifyKeyframes(views.a, views.b, options);
  EXPECT_FALSE(result.verified);
  EXPECT_NE(result.reason.find("grid cells"), std::string::npos) << result.reason;
}

TEST(GeometricVerifierTest, UnrelatedImagesAreNotVerified) {
  const sensor::PinholeIntrinsics in = testing::TestIntrinsics();
  const OrbExtractor extractor{OrbOptions{}};
  const cv::Mat depth(in.height, in.width, CV_32FC1, cv::Scalar(kPlaneDepthM));
  const Keyframe a = MakeKeyframe(testing::RandomTexture(in.width, in.height, 1), depth, in,
                                  extractor, nullptr, KeyframeOptions{});
  const Keyframe b = MakeKeyframe(testing::RandomTexture(in.width, in.height, 2), cv::Mat(), in,
                                  extractor, nullptr, KeyframeOptions{});
  const VerificationResult result = VerifyKeyframes(a, b, VerificationOptions{});
  EXPECT_FALSE(result.verified);
  EXPECT_FALSE(result.reason.empty());
}

}  // namespace
}  // namespace visual_loop
}  // namespace fusemap
