#include "fusemap/visual_loop/visual_loop_checker.h"

#include <gtest/gtest.h>

#include "visual_loop/synthetic_views.h"

namespace fusemap {
namespace visual_loop {
namespace {

constexpr double kPlaneDepthM = 2.0;

common::Rigid3d CameraMount() { return testing::CameraMount(0.5, 0.0); }

CameraFrame Frame(const cv::Mat& image, bool with_depth, double stamp_s) {
  CameraFrame frame;
  frame.stamp_s = stamp_s;
  frame.image = image;
  frame.intrinsics = testing::TestIntrinsics();
  if (with_depth) frame.depth_m = cv::Mat(image.size(), CV_32FC1, cv::Scalar(kPlaneDepthM));
  frame.T_base_camera = CameraMount();
  return frame;
}

std::unique_ptr<VisualLoopChecker> MakeChecker(const VisualLoopCheckerOptions& options) {
  std::string error;
  auto vocabulary =
      Vocabulary::Load(std::string(FUSEMAP_SOURCE_DIR) + "/data/vocabulary/orb_k10_l4.bin", &error);
  EXPECT_TRUE(vocabulary) << error;
  if (!vocabulary) return nullptr;
  return std::make_unique<VisualLoopChecker>(
      options, std::make_shared<const Vocabulary>(std::move(*vocabulary)));
}

class VisualLoopCheckerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    checker_ = MakeChecker(VisualLoopCheckerOptions{});
    ASSERT_TRUE(checker_);
    const sensor::PinholeIntrinsics in = testing::TestIntrinsics();
    const cv::Mat place = testing::RandomTexture(in.width, in.height, 21);
    // Keyframe 0: the place, with depth. Keyframe 1: the same place, the base 0.2 m further and
    // turned 3 degrees. Keyframe 2: another place. Keyframe 3: a blank wall.
    const common::Rigid3d T_base_a_base_b = common::Rigid3d::FromRigid2d(truth_);
    const common::Rigid3d T_camera_a_camera_b = CameraMount().inverse() * T_base_a_base_b * CameraMount();
    const cv::Mat revisit = testing::WarpToView(place, T_camera_a_camera_b, in, kPlaneDepthM);
    const cv::Mat other = testing::RandomTexture(in.width, in.height, 22);
    const cv::Mat blank(in.height, in.width, CV_8UC1, cv::Scalar(100));
    const cv::Mat images[] = {place, revisit, other, blank};
    for (int i = 0; i < 4; ++i) {
      const auto result = checker_->AddFrame(Frame(images[i], i == 0, i * 1.0),
                                             common::Rigid2d(i * 1.0, 0.0, 0.0), 10 * i, i < 2 ? 0 : 1);
      EXPECT_TRUE(result.keyframe) << i;
      EXPECT_FALSE(result.loop) << i;  // all are recent: never loop candidates
    }
  }

  const common::Rigid2d truth_{0.2, 0.0, 3.0 * M_PI / 180.0};
  std::unique_ptr<VisualLoopChecker> checker_;
};

TEST_F(VisualLoopCheckerTest, VerifiesTheSamePlaceAsAPlanarConstraint) {
  const VisualCheckResult result = checker_->CheckPlace(1, 0, truth_);
  ASSERT_EQ(result.check, VisualCheck::kVerified) << result.reason;
  ASSERT_TRUE(result.constraint);
  EXPECT_NEAR(result.constraint->T_match_base_query_base.x(), 0.2, 0.005);
  EXPECT_NEAR(result.constraint->T_match_base_query_base.y(), 0.0, 0.005);
  EXPECT_NEAR(result.constraint->T_match_base_query_base.angle_rad(), truth_.angle_rad(), 0.002);
  EXPECT_EQ(result.constraint->match_node, 0);
  EXPECT_EQ(result.constraint->query_node, 10);
  EXPECT_EQ(result.constraint->match_submap, 0);
  // In a submap where the matched base stands at (5, 1), turned 90 degrees.
  const LoopMeasurement2D m = ToSubmapMeasurement(common::Rigid2d(5.0, 1.0, M_PI / 2), *result.constraint);
  EXPECT_NEAR(m.T_submap_node.x(), 5.0, 0.005);
  EXPECT_NEAR(m.T_submap_node.y(), 1.2, 0.005);
  EXPECT_NEAR(m.covariance(0, 0), result.constraint->covariance(1, 1), 1e-12);
}

TEST_F(VisualLoopCheckerTest, ContradictsOnlyWhereRichViewsShouldOverlap) {
  EXPECT_EQ(checker_->CheckPlace(2, 0, truth_).check, VisualCheck::kContradicted);
  // The laser puts them 3 m apart: the camera has no say.
  EXPECT_EQ(checker_->CheckPlace(2, 0, common::Rigid2d(3.0, 0.0, 0.0)).check, VisualCheck::kNotChecked);
  // A blank wall cannot contradict anything.
  EXPECT_EQ(checker_->CheckPlace(3, 0, truth_).check, VisualCheck::kNotChecked);
  EXPECT_EQ(checker_->CheckPlace(7, 0, truth_).check, VisualCheck::kNotChecked);
}

// Pixels are held for the two latest keyframes only: a match between them (a motion link) is
// refined on them, one with an older keyframe is not. A pair is verified once: asked again
// later (a laser loop's check), it keeps what its first verification measured.
TEST(VisualLoopCheckerPixelsTest, RefinesOnlyBetweenTheTwoLatestKeyframes) {
  for (const bool enabled : {true, false}) {
    VisualLoopCheckerOptions options;
    options.refine_latest_on_pixels = enabled;
    const sensor::PinholeIntrinsics in = testing::TestIntrinsics();
    const common::Rigid2d truth(0.3, 0.0, 0.0);  // straight towards the wall
    const cv::Mat place = testing::RandomTexture(in.width, in.height, 31);
    const cv::Mat closer = testing::WarpToView(
        place, CameraMount().inverse() * common::Rigid3d::FromRigid2d(truth) * CameraMount(), in,
        kPlaneDepthM);
    const cv::Mat other = testing::RandomTexture(in.width, in.height, 32);
    const auto add_place = [&](VisualLoopChecker* checker) {
      EXPECT_TRUE(
          checker->AddFrame(Frame(place, true, 0.0), common::Rigid2d::Identity(), 0, 0).keyframe);
      EXPECT_TRUE(checker->AddFrame(Frame(closer, true, 1.0), truth, 1, 0).keyframe);
    };
    // Two more keyframes: 0 and 1 are no longer the latest, their pixels are gone.
    const auto move_on = [&](VisualLoopChecker* checker) {
      EXPECT_TRUE(checker->AddFrame(Frame(other, true, 2.0), common::Rigid2d(1.0, 0.0, 0.0), 2, 0)
                      .keyframe);
      EXPECT_TRUE(checker->AddFrame(Frame(other, true, 3.0), common::Rigid2d(2.0, 0.0, 0.0), 3, 0)
                      .keyframe);
    };

    const std::unique_ptr<VisualLoopChecker> checker = MakeChecker(options);
    ASSERT_TRUE(checker);
    add_place(checker.get());
    const VisualCheckResult latest = checker->CheckPlace(1, 0, truth);
    ASSERT_EQ(latest.check, VisualCheck::kVerified) << latest.reason;
    EXPECT_EQ(latest.refined_on_pixels, enabled);
    EXPECT_EQ(latest.aligned_points >= options.patch_alignment.min_points, enabled)
        << latest.aligned_points;
    EXPECT_NEAR(latest.constraint->T_match_base_query_base.x(), 0.3, 0.002);
    move_on(checker.get());
    const VisualCheckResult again = checker->CheckPlace(1, 0, truth);
    ASSERT_EQ(again.check, VisualCheck::kVerified) << again.reason;
    EXPECT_EQ(again.refined_on_pixels, latest.refined_on_pixels);
    EXPECT_EQ(again.aligned_points, latest.aligned_points);
    EXPECT_EQ(again.constraint->T_match_base_query_base.x(),
              latest.constraint->T_match_base_query_base.x());

    // The same pair first asked about once its pixels are gone.
    const std::unique_ptr<VisualLoopChecker> later = MakeChecker(options);
    ASSERT_TRUE(later);
    add_place(later.get());
    move_on(later.get());
    const VisualCheckResult older = later->CheckPlace(1, 0, truth);
    ASSERT_EQ(older.check, VisualCheck::kVerified) << older.reason;
    EXPECT_FALSE(older.refined_on_pixels);
    EXPECT_EQ(older.aligned_points, 0);
  }
}

TEST_F(VisualLoopCheckerTest, KeyframesAreFoundByNodeAndReleasedWithTheirSubmap) {
  EXPECT_EQ(checker_->stats().keyframes, 4);
  EXPECT_EQ(checker_->KeyframeNearestNode(12), 1);
  EXPECT_EQ(checker_->KeyframesOfSubmap(1), (std::vector<int>{2, 3}));
  checker_->RemoveSubmap(1);
  EXPECT_TRUE(checker_->KeyframesOfSubmap(1).empty());
  EXPECT_EQ(checker_->stats().keyframes, 2);
  EXPECT_EQ(checker_->KeyframeNearestNode(30), 1);
}

}  // namespace
}  // namespace visual_loop
}  // namespace fusemap
