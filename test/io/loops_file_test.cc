#include "fusemap/io/loops_file.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

namespace fusemap {
namespace io {
namespace {

std::string ReadAll(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(LoopsFileTest, HeaderThenOneLinePerDecision) {
  visual_loop::LoopMeasurement2D laser;
  laser.T_submap_node = common::Rigid2d({1.5, -2.0}, 0.25);
  laser.laser_score = 0.71;
  visual_loop::LoopMeasurement2D visual;
  visual.T_submap_node = common::Rigid2d({1.0, -2.0}, 0.2);
  visual.visual_inliers = 120;
  visual_loop::ArbitrationRecord overridden;
  overridden.node = 42;
  overridden.submap = 3;
  overridden.source = visual_loop::LoopSource::kBoth;
  overridden.decision = visual_loop::LoopDecision::kVisualOverride;
  overridden.laser = laser;
  overridden.visual = visual;
  overridden.chosen = visual;
  overridden.translation_disagreement_m = 0.5;
  overridden.rotation_disagreement_rad = 0.05;
  overridden.reason = "disagree\tby a lot";
  visual_loop::ArbitrationRecord rejected;
  rejected.node = 7;
  rejected.submap = 0;
  rejected.decision = visual_loop::LoopDecision::kLaserRejected;
  rejected.laser = laser;
  rejected.laser->unmeasured_direction = Eigen::Vector2d(0.6, 0.8);
  rejected.laser->unmeasured_turn_rad_per_m = 0.0714;
  rejected.reason = "contradicted";

  const std::string path = ::testing::TempDir() + "/loops_file_test.tsv";
  std::string error;
  ASSERT_TRUE(WriteLoopsTsv(path, {overridden, rejected}, &error)) << error;
  EXPECT_EQ(ReadAll(path),
            std::string(kLoopsTsvHeader) + "\n" +
                "42\t3\tboth\t0.7100\t120\tvisual_override\t1.0000\t-2.0000\t0.20000\t0.5000\t"
                "0.05000\t0.0000\t0.0000\t0.00000\tdisagree by a lot\n"
                "7\t0\tlaser\t0.7100\t0\tlaser_rejected\t1.5000\t-2.0000\t0.25000\t0.0000\t"
                "0.00000\t0.6000\t0.8000\t0.07140\tcontradicted\n");
  EXPECT_FALSE(WriteLoopsTsv("/nonexistent/dir/loops.tsv", {}, &error));
  EXPECT_NE(error.find("/nonexistent/dir/loops.tsv"), std::string::npos) << error;
}

}  // namespace
}  // namespace io
}  // namespace fusemap
