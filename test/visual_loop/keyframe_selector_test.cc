#include "fusemap/visual_loop/keyframe_selector.h"

#include <gtest/gtest.h>

namespace fusemap {
namespace visual_loop {
namespace {

TEST(KeyframeSelectorTest, MotionTurnAndTimeEachMakeAKeyframe) {
  KeyframeSelector selector{KeyframeSelectorOptions{}};
  EXPECT_TRUE(selector.Select(0.0, common::Rigid2d(0.0, 0.0, 0.0)));   // the first frame
  EXPECT_FALSE(selector.Select(0.5, common::Rigid2d(0.2, 0.0, 0.0)));  // 0.2 m < 0.3 m
  EXPECT_TRUE(selector.Select(1.0, common::Rigid2d(0.31, 0.0, 0.0)));
  EXPECT_FALSE(selector.Select(1.5, common::Rigid2d(0.31, 0.0, 0.3)));  // 17 deg < 20 deg
  EXPECT_TRUE(selector.Select(2.0, common::Rigid2d(0.31, 0.0, 0.4)));
  EXPECT_FALSE(selector.Select(11.0, common::Rigid2d(0.31, 0.0, 0.4)));  // 9 s standing still
  EXPECT_TRUE(selector.Select(12.5, common::Rigid2d(0.31, 0.0, 0.4)));   // 10.5 s
}

TEST(KeyframeSelectorTest, NeverFasterThanTheMinimumInterval) {
  KeyframeSelector selector{KeyframeSelectorOptions{}};
  EXPECT_TRUE(selector.Select(0.0, common::Rigid2d(0.0, 0.0, 0.0)));
  EXPECT_FALSE(selector.Select(0.1, common::Rigid2d(5.0, 0.0, 0.0)));  // a jump, 0.1 s later
  EXPECT_TRUE(selector.Select(0.3, common::Rigid2d(5.0, 0.0, 0.0)));
  // Keyframes per metre driven stay a few at most.
  int keyframes = 0;
  for (int i = 1; i <= 100; ++i) keyframes += selector.Select(0.3 + 0.05 * i, common::Rigid2d(5.0 + 0.05 * i, 0.0, 0.0));
  EXPECT_LE(keyframes, 17);  // 5 m at >= 0.3 m apart
  std::string error;
  EXPECT_TRUE(KeyframeSelectorOptions{}.IsValid(&error));
  KeyframeSelectorOptions bad;
  bad.min_translation_m = 0.0;
  EXPECT_FALSE(bad.IsValid(&error));
}

}  // namespace
}  // namespace visual_loop
}  // namespace fusemap
