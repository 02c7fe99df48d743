#include "fusemap/io/loop_tables_file.h"

#include <gtest/gtest.h>

#include <sstream>

#include "fusemap/io/loops_file.h"

namespace fusemap {
namespace io {
namespace {

TEST(LoopTablesFileTest, ReadsLoopsWithHeaderAndDegrees) {
  std::istringstream in(
      "# loops\nnode submap source laser_score visual_inliers decision x y yaw_deg\n"
      "12 3 both 0.71 85 laser_confirmed 1.5 -0.25 90\n\n4 0 visual 0 40 visual_forced 0 0 0\n");
  std::vector<eval::LoopRecord> loops;
  std::string error;
  ASSERT_TRUE(ReadLoops(in, "loops.tsv", &loops, &error)) << error;
  ASSERT_EQ(loops.size(), 2u);
  // Written before the unmeasured_x/unmeasured_y columns: measured every way.
  EXPECT_TRUE(loops[0].unmeasured_direction.isZero());
  EXPECT_EQ(loops[0].node, 12);
  EXPECT_EQ(loops[0].submap, 3);
  EXPECT_EQ(loops[0].source, "both");
  EXPECT_DOUBLE_EQ(loops[0].laser_score, 0.71);
  EXPECT_EQ(loops[0].visual_inliers, 85);
  EXPECT_EQ(loops[0].decision, "laser_confirmed");
  EXPECT_DOUBLE_EQ(loops[0].T_submap_node.x(), 1.5);
  EXPECT_NEAR(loops[0].T_submap_node.angle_rad(), 1.5707963267948966, 1e-12);
  EXPECT_EQ(loops[1].decision, "visual_forced");
}

TEST(LoopTablesFileTest, ExtraTabSeparatedColumnsWithSpacesAreIgnored) {
  std::istringstream in(
      "node\tsubmap\tsource\tlaser_score\tvisual_inliers\tdecision\tx_m\ty_m\tyaw_rad\t"
      "disagreement_m\treason\n"
      "5\t1\tboth\t0.6\t44\tvisual_override\t1\t2\t0.5\t0.8\tdisagree by 0.8 m\n"
      "6\t1\tlaser\t0.7\t0\tlaser_kept\t1\t2\t0.5\t0\t\n");
  std::vector<eval::LoopRecord> loops;
  std::string error;
  ASSERT_TRUE(ReadLoops(in, "loops.tsv", &loops, &error)) << error;
  ASSERT_EQ(loops.size(), 2u);
  EXPECT_EQ(loops[0].decision, "visual_override");
  EXPECT_DOUBLE_EQ(loops[0].T_submap_node.angle_rad(), 0.5);
  EXPECT_EQ(loops[1].node, 6);
}

TEST(LoopTablesFileTest, ErrorsNameLineAndField) {
  std::vector<eval::LoopRecord> loops;
  std::string error;
  std::istringstream short_line("1 2 laser 0.5 0 laser_kept 1 2\n");
  EXPECT_FALSE(ReadLoops(short_line, "l.tsv", &loops, &error));
  EXPECT_NE(error.find("l.tsv:1: expected 9 fields"), std::string::npos) << error;
  std::istringstream bad_node("\n-1 2 laser 0.5 0 laser_kept 1 2 3\n");
  EXPECT_FALSE(ReadLoops(bad_node, "l.tsv", &loops, &error));
  EXPECT_NE(error.find("l.tsv:2: node '-1'"), std::string::npos) << error;
  std::istringstream bad_x("1 2 laser 0.5 0 laser_kept nan 2 3\n");
  EXPECT_FALSE(ReadLoops(bad_x, "l.tsv", &loops, &error));
  EXPECT_NE(error.find("x 'nan' is not a finite number"), std::string::npos) << error;
}

TEST(LoopTablesFileTest, ReadsSubmapAnchors) {
  std::istringstream in("submap first_node x y yaw\n0 0 0 0 0\n1 58 3.5 0.25 -0.1\n");
  std::vector<eval::SubmapAnchor> submaps;
  std::string error;
  ASSERT_TRUE(ReadSubmapAnchors(in, "s.tsv", &submaps, &error)) << error;
  ASSERT_EQ(submaps.size(), 2u);
  EXPECT_EQ(submaps[1].first_node, 58);
  EXPECT_DOUBLE_EQ(submaps[1].T_map_submap.y(), 0.25);
  EXPECT_FALSE(ReadSubmapAnchorsFile("/nonexistent/submaps.tsv", &submaps, &error));
  EXPECT_NE(error.find("cannot open"), std::string::npos);
}

TEST(LoopTablesFileTest, WrittenTablesReadBack) {
  const std::string dir = ::testing::TempDir();
  // loops.tsv as the session writes it (io::WriteLoopsTsv).
  std::vector<visual_loop::ArbitrationRecord> loops(1);
  loops[0].node = 7;
  loops[0].submap = 2;
  loops[0].laser = visual_loop::LoopMeasurement2D{common::Rigid2d(1.25, -3.5, 0.75)};
  loops[0].laser->laser_score = 0.625;
  loops[0].laser->unmeasured_direction = Eigen::Vector2d(0.0, -1.0);
  loops[0].laser->unmeasured_turn_rad_per_m = -0.125;
  std::vector<eval::SubmapAnchor> submaps = {{2, 60, common::Rigid2d(4, 5, -1.5)}};
  std::string error;
  ASSERT_TRUE(WriteLoopsTsv(dir + "/loops.tsv", loops, &error)) << error;
  ASSERT_TRUE(WriteSubmapAnchorsFile(dir + "/submaps.tsv", submaps, &error)) << error;
  std::vector<eval::LoopRecord> loops_read;
  std::vector<eval::SubmapAnchor> submaps_read;
  ASSERT_TRUE(ReadLoopsFile(dir + "/loops.tsv", &loops_read, &error)) << error;
  ASSERT_TRUE(ReadSubmapAnchorsFile(dir + "/submaps.tsv", &submaps_read, &error)) << error;
  ASSERT_EQ(loops_read.size(), 1u);
  EXPECT_EQ(loops_read[0].node, 7);
  EXPECT_EQ(loops_read[0].source, "laser");
  EXPECT_EQ(loops_read[0].decision, "laser_kept");
  EXPECT_DOUBLE_EQ(loops_read[0].laser_score, 0.625);
  EXPECT_DOUBLE_EQ(loops_read[0].T_submap_node.x(), 1.25);
  EXPECT_DOUBLE_EQ(loops_read[0].T_submap_node.angle_rad(), 0.75);
  EXPECT_EQ(loops_read[0].unmeasured_direction, Eigen::Vector2d(0.0, -1.0));
  EXPECT_DOUBLE_EQ(loops_read[0].unmeasured_turn_rad_per_m, -0.125);
  ASSERT_EQ(submaps_read.size(), 1u);
  EXPECT_EQ(submaps_read[0].first_node, 60);
  EXPECT_DOUBLE_EQ(submaps_read[0].T_map_submap.x(), 4.0);
  EXPECT_FALSE(WriteSubmapAnchorsFile("/nonexistent/dir/submaps.tsv", submaps, &error));
  EXPECT_NE(error.find("write failed"), std::string::npos) << error;
}

}  // namespace
}  // namespace io
}  // namespace fusemap
