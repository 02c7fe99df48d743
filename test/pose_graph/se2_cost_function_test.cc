#include "fusemap/pose_graph/se2_cost_function.h"

#include <gtest/gtest.h>

#include <Eigen/Core>

namespace fusemap {
namespace pose_graph {
namespace {

TEST(Se2CostFunctionTest, WeakenModeKeepsTheFractionAlongTheModeAndTheRestAsIs) {
  const Eigen::Matrix3d information = InformationFromWeights(100.0, 300.0);
  // Forward along x while turning 0.1 rad a metre: a slide round a curved wall of radius 10 m.
  const Eigen::Vector3d mode(1.0, 0.0, 0.1);
  const Eigen::Matrix3d weak = WeakenMode(information, mode, 0.01);
  EXPECT_NEAR(mode.dot(weak * mode), 1e-4 * mode.dot(information * mode),
              1e-9 * mode.dot(information * mode));
  // Across the corridor, and what is orthogonal to the mode in the information's metric (a turn
  // with the slide that holds it back), keep all of it.
  const Eigen::Vector3d across(0.0, 1.0, 0.0);
  EXPECT_NEAR(across.dot(weak * across), across.dot(information * across), 1e-6);
  const Eigen::Vector3d other(-0.1 * 300.0 * 300.0 / (100.0 * 100.0), 0.0, 1.0);
  ASSERT_NEAR(other.dot(information * mode), 0.0, 1e-9);
  EXPECT_NEAR(other.dot(weak * other), other.dot(information * other), 1e-6);
  Eigen::Matrix3d sqrt_information;
  EXPECT_TRUE(SqrtInformation(weak, &sqrt_information));
}

TEST(Se2CostFunctionTest, WithoutATurnTheModeIsTheTranslationAlongTheDirection) {
  const Eigen::Vector2d along(0.6, -0.8);
  const Eigen::Matrix3d straight = InformationWithoutMode(50.0, 70.0, along, 0.0);
  EXPECT_TRUE(straight.isApprox(InformationFromWeights(50.0, 70.0, along, 1e-3), 1e-12));
  EXPECT_NEAR(Eigen::Vector3d(0.6, -0.8, 0.0).dot(straight * Eigen::Vector3d(0.6, -0.8, 0.0)),
              1e-6 * 50.0 * 50.0, 1e-9);
  EXPECT_NEAR(straight(2, 2), 70.0 * 70.0, 1e-9);
  // None unmeasured: the plain weights.
  EXPECT_TRUE(InformationWithoutMode(50.0, 70.0, Eigen::Vector2d::Zero(), 0.3)
                  .isApprox(InformationFromWeights(50.0, 70.0)));
  // With a turn, the heading alone is no longer fully held: sliding and turning together cost
  // almost nothing.
  const Eigen::Matrix3d curved = InformationWithoutMode(50.0, 70.0, along, 0.2);
  const Eigen::Vector3d slide(0.6, -0.8, 0.2);
  EXPECT_LT(slide.dot(curved * slide),
            1e-5 * slide.dot(InformationFromWeights(50.0, 70.0) * slide));
  EXPECT_LT(curved(2, 2), 70.0 * 70.0);
}

}  // namespace
}  // namespace pose_graph
}  // namespace fusemap
