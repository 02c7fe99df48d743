#include "fusemap/visual_loop/patch_alignment.h"

#include <algorithm>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "fusemap/visual_loop/pose_covariance.h"
#include "visual_loop/synthetic_views.h"

namespace fusemap {
namespace visual_loop {
namespace {

constexpr double kPlaneDepthM = 2.0;

// Camera b 0.6 m closer to the textured plane than a (it sees it 1.4x larger), a little to the
// side and turned: the motion between two keyframes in a corridor.
common::Rigid3d StepTowardsThePlane() {
  return testing::PoseFromTranslationRpy(0.05, -0.02, 0.6, 0.01, -0.03, 0.02);
}

struct Views {
  CameraImage a;
  CameraImage b;
};

Views MakeViews(const common::Rigid3d& T_a_b) {
  Views views;
  const sensor::PinholeIntrinsics in = testing::TestIntrinsics();
  views.a.gray = testing::RandomTexture(in.width, in.height, 11);
  views.a.depth_m = cv::Mat(in.height, in.width, CV_32FC1, cv::Scalar(kPlaneDepthM));
  views.a.intrinsics = in;
  views.b.gray = testing::WarpToView(views.a.gray, T_a_b, in, kPlaneDepthM);
  views.b.intrinsics = in;
  return views;
}

// The views' keyframes, with depth in a (as the checker keeps them).
struct Keyframes {
  Keyframe a;
  Keyframe b;
};

Keyframes MakeKeyframes(const Views& views) {
  const OrbExtractor extractor{OrbOptions{}};
  return {MakeKeyframe(views.a.gray, views.a.depth_m, views.a.intrinsics, extractor, nullptr, {}),
          MakeKeyframe(views.b.gray, cv::Mat(), views.b.intrinsics, extractor, nullptr, {})};
}

// Corners of a's texture in the middle of the image (the kind of point a keypoint is), each
// moved off the pixel grid.
std::vector<Eigen::Vector2d> CornersOf(const cv::Mat& gray, int count) {
  cv::Mat mask = cv::Mat::zeros(gray.size(), CV_8UC1);
  mask(cv::Rect(160, 120, 320, 240)).setTo(cv::Scalar(255));
  std::vector<cv::Point2f> corners;
  cv::goodFeaturesToTrack(gray, corners, count, 0.05, 12.0, mask);
  std::vector<Eigen::Vector2d> pixels;
  for (const cv::Point2f& c : corners) pixels.emplace_back(c.x + 0.3, c.y - 0.4);
  return pixels;
}

Eigen::Vector3d PointOnThePlane(const sensor::PinholeIntrinsics& in, const Eigen::Vector2d& pixel) {
  return kPlaneDepthM *
         Eigen::Vector3d((pixel.x() - in.cx) / in.fx, (pixel.y() - in.cy) / in.fy, 1.0);
}

TEST(PatchAlignmentTest, FindsThePointWhereTheKeypointInBIsOff) {
  const common::Rigid3d T_a_b = StepTowardsThePlane();
  const Views views = MakeViews(T_a_b);
  const sensor::PinholeIntrinsics& in = views.a.intrinsics;
  // The pose the alignment starts from is 1 cm and 0.2 degrees off (a PnP estimate's error):
  // its prediction in b is a few pixels off the truth.
  const common::Rigid3d T_b_a_estimate =
      testing::PoseFromTranslationRpy(0.01, 0.005, -0.005, 0.0, 0.0035, 0.0) * T_a_b.inverse();
  const PatchAlignmentOptions options;
  int aligned = 0;
  int tried = 0;
  double error_sum_px = 0.0;
  double worst_px = 0.0;
  for (const Eigen::Vector2d& pixel_a : CornersOf(views.a.gray, 60)) {
    const Eigen::Vector3d point_a = PointOnThePlane(in, pixel_a);
    const Eigen::Vector2d truth_b = Project(in, T_a_b.inverse() * point_a);
    // The detector put the keypoint in b 1.2 px off the point.
    const Eigen::Vector2d keypoint_b = truth_b + Eigen::Vector2d(1.0, -0.7);
    ++tried;
    const std::optional<Eigen::Vector2d> found =
        AlignPatch(views.a, views.b, T_b_a_estimate, pixel_a, point_a, keypoint_b, options);
    if (!found) continue;
    ++aligned;
    const double error_px = (*found - truth_b).norm();
    error_sum_px += error_px;
    worst_px = std::max(worst_px, error_px);
  }
  ASSERT_GE(tried, 40);
  EXPECT_GE(aligned, tried * 9 / 10);
  EXPECT_LT(error_sum_px / aligned, 0.05);
  EXPECT_LT(worst_px, 0.3);
}

TEST(PatchAlignmentTest, HoldsUnderALightingChange) {
  const common::Rigid3d T_a_b = StepTowardsThePlane();
  Views views = MakeViews(T_a_b);
  views.b.gray.convertTo(views.b.gray, CV_8UC1, 0.6, 12.0);  // darker, lifted blacks
  const sensor::PinholeIntrinsics& in = views.a.intrinsics;
  const Eigen::Vector2d pixel_a = CornersOf(views.a.gray, 1).at(0);
  const Eigen::Vector3d point_a = PointOnThePlane(in, pixel_a);
  const Eigen::Vector2d truth_b = Project(in, T_a_b.inverse() * point_a);
  const std::optional<Eigen::Vector2d> found =
      AlignPatch(views.a, views.b, T_a_b.inverse(), pixel_a, point_a,
                 truth_b + Eigen::Vector2d(0.8, 0.8), PatchAlignmentOptions{});
  ASSERT_TRUE(found);
  EXPECT_LT((*found - truth_b).norm(), 0.1);
}

TEST(PatchAlignmentTest, RefusesAPatchWithoutTextureAndOneLeavingTheImage) {
  const common::Rigid3d T_a_b = StepTowardsThePlane();
  Views views = MakeViews(T_a_b);
  const sensor::PinholeIntrinsics& in = views.a.intrinsics;
  const Eigen::Vector2d pixel_a(320.0, 240.0);
  const Eigen::Vector3d point_a = PointOnThePlane(in, pixel_a);
  const Eigen::Vector2d truth_b = Project(in, T_a_b.inverse() * point_a);
  views.b.gray.setTo(cv::Scalar(128));
  EXPECT_FALSE(AlignPatch(views.a, views.b, T_a_b.inverse(), pixel_a, point_a, truth_b,
                          PatchAlignmentOptions{}));
  // A point at a's border: its patch is not all inside a.
  const Eigen::Vector2d border_a(3.0, 240.0);
  EXPECT_FALSE(AlignPatch(
      views.a, views.b, T_a_b.inverse(), border_a, PointOnThePlane(in, border_a),
      Project(in, T_a_b.inverse() * PointOnThePlane(in, border_a)), PatchAlignmentOptions{}));
}

TEST(PatchAlignmentTest, RefusesAPointFurtherThanMaxShiftFromItsKeypoint) {
  const common::Rigid3d T_a_b = StepTowardsThePlane();
  const Views views = MakeViews(T_a_b);
  const sensor::PinholeIntrinsics& in = views.a.intrinsics;
  const Eigen::Vector2d pixel_a = CornersOf(views.a.gray, 1).at(0);
  const Eigen::Vector3d point_a = PointOnThePlane(in, pixel_a);
  const Eigen::Vector2d truth_b = Project(in, T_a_b.inverse() * point_a);
  PatchAlignmentOptions options;
  ASSERT_TRUE(AlignPatch(views.a, views.b, T_a_b.inverse(), pixel_a, point_a, truth_b, options));
  // The descriptor matched a keypoint 5 px from where the patch is: not this point.
  EXPECT_FALSE(AlignPatch(views.a, views.b, T_a_b.inverse(), pixel_a, point_a,
                          truth_b + Eigen::Vector2d(5.0, 0.0), options));
}

TEST(PatchAlignmentTest, RefinedPnpIsCloserToTheTruth) {
  const common::Rigid3d T_a_b = StepTowardsThePlane();
  const Views views = MakeViews(T_a_b);
  const Keyframes keyframes = MakeKeyframes(views);
  const Keyframe& a = keyframes.a;
  const Keyframe& b = keyframes.b;
  VerificationResult result = VerifyKeyframes(a, b, VerificationOptions{});
  ASSERT_TRUE(result.verified) << result.reason;
  const double before_m = (result.T_a_b.translation() - T_a_b.translation()).norm();
  const int aligned =
      RefineByPatchAlignment(a, views.a, b, views.b, PatchAlignmentOptions{}, &result);
  // Nearly all of those tried (every inlier, or max_points spread over them) align.
  const int tried = std::min(result.inliers, PatchAlignmentOptions{}.max_points);
  EXPECT_LE(aligned, tried);
  EXPECT_GE(aligned, tried * 8 / 10);
  const double after_m = (result.T_a_b.translation() - T_a_b.translation()).norm();
  std::cout << "PnP " << result.inliers << " inliers, " << aligned << " aligned: error "
            << before_m * 1000.0 << " -> " << after_m * 1000.0 << " mm\n";
  EXPECT_LT(after_m, 0.5 * before_m);
  EXPECT_LT(after_m, 0.001);
  EXPECT_LT(testing::AngleBetweenDeg(result.T_a_b, T_a_b), 0.02);
  EXPECT_LT(result.mean_reprojection_px, 0.2);
}

TEST(PatchAlignmentTest, RefineAlignsAtMostMaxPointsSpreadOverTheInliers) {
  const common::Rigid3d T_a_b = StepTowardsThePlane();
  const Views views = MakeViews(T_a_b);
  const Keyframes keyframes = MakeKeyframes(views);
  VerificationResult result = VerifyKeyframes(keyframes.a, keyframes.b, VerificationOptions{});
  ASSERT_TRUE(result.verified) << result.reason;
  ASSERT_GT(result.inliers, 120);
  PatchAlignmentOptions options;
  options.max_points = 40;
  const int aligned =
      RefineByPatchAlignment(keyframes.a, views.a, keyframes.b, views.b, options, &result);
  EXPECT_LE(aligned, 40);
  EXPECT_GE(aligned, 32);
  EXPECT_LT((result.T_a_b.translation() - T_a_b.translation()).norm(), 0.002);
}

TEST(PatchAlignmentTest, RefineLeavesAResultWithTooFewAlignedPoints) {
  const common::Rigid3d T_a_b = StepTowardsThePlane();
  Views views = MakeViews(T_a_b);
  const Keyframes keyframes = MakeKeyframes(views);
  const Keyframe& a = keyframes.a;
  const Keyframe& b = keyframes.b;
  VerificationResult result = VerifyKeyframes(a, b, VerificationOptions{});
  ASSERT_TRUE(result.verified) << result.reason;
  const VerificationResult before = result;
  views.b.gray.setTo(cv::Scalar(128));  // nothing to align against
  EXPECT_EQ(RefineByPatchAlignment(a, views.a, b, views.b, PatchAlignmentOptions{}, &result), 0);
  EXPECT_EQ(result.T_a_b.translation(), before.T_a_b.translation());
  EXPECT_EQ(result.mean_reprojection_px, before.mean_reprojection_px);
}

TEST(PatchAlignmentOptionsTest, Validates) {
  std::string error;
  EXPECT_TRUE(PatchAlignmentOptions{}.IsValid(&error));
  PatchAlignmentOptions bad;
  bad.half_window_px = 1;
  EXPECT_FALSE(bad.IsValid(&error));
  bad = PatchAlignmentOptions{};
  bad.max_shift_px = 0.0;
  EXPECT_FALSE(bad.IsValid(&error));
  bad = PatchAlignmentOptions{};
  bad.max_points = 5;
  EXPECT_FALSE(bad.IsValid(&error));
  bad = PatchAlignmentOptions{};
  bad.min_points = 5;
  EXPECT_FALSE(bad.IsValid(&error));
  bad = PatchAlignmentOptions{};
  bad.min_points = bad.max_points + 1;
  EXPECT_FALSE(bad.IsValid(&error));
}

}  // namespace
}  // namespace visual_loop
}  // namespace fusemap
