#include "fusemap/io/report_writer.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fusemap {
namespace io {
namespace {

namespace fs = std::filesystem;

ground_truth::TrajectoryScore MakeScore() {
  ground_truth::TrajectoryScore s;
  s.gt_poses = 3;
  s.est_poses = 3;
  s.associated = 3;
  s.gt_length_m = 2.0;
  s.ate.trans_m.rmse = 0.123;
  s.ate.unaligned_rmse_m = 0.987;
  s.rpe.trans_m.rmse = 0.0456;
  s.rpe_trans_per_m = 0.0456;
  s.has_loop = true;
  s.loop_error_m = 0.0321;
  s.stamps_s = {10.0, 11.0, 12.0};
  s.gt_positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
  s.est_positions_aligned = {{0, 0.1, 0}, {1, 0.1, 0}, {1.1, 1, 0}};
  s.position_errors_m = {0.1, 0.1, 0.1};
  ground_truth::TagResidual r;
  r.tag_id = 17;
  r.position_error_m.count = 4;
  r.position_error_m.mean = 0.0077;
  s.tag_residuals.push_back(r);
  s.measures.push_back({"door", "pillar <3>", 5.0, 5.02, 0.02});
  return s;
}

std::string Slurp(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(ReportWriterTest, WritesHtmlAndJsonWithTheSameFigures) {
  const fs::path dir = fs::temp_directory_path() / "fusemap_report_writer_test" / "nested";
  fs::remove_all(dir.parent_path());
  ReportInfo info;
  info.gt_path = "gt.tum";
  info.est_path = "est.tum";
  std::string error;
  ASSERT_TRUE(WriteScoreReport(dir.string(), MakeScore(), info, &error)) << error;
  const std::string json = Slurp(dir / "report.json");
  const std::string html = Slurp(dir / "index.html");
  for (const std::string& needle :
       {std::string("\"ate_rmse_m\": 0.123"), std::string("\"ate_unaligned_rmse_m\": 0.987"),
        std::string("\"rpe_trans_per_m\": 0.0456"), std::string("\"loop_error_m\": 0.0321"),
        std::string("\"tag_id\": 17"), std::string("\"map_m\": 5.02"),
        std::string("\"gt\": \"gt.tum\"")}) {
    EXPECT_NE(json.find(needle), std::string::npos) << needle << "\n" << json;
  }
  for (const auto& figure : ReportFigures(MakeScore())) {
    EXPECT_NE(html.find("data-key=\"" + figure.key + "\""), std::string::npos) << figure.key;
    EXPECT_NE(json.find("\"" + figure.key + "\""), std::string::npos) << figure.key;
  }
  EXPECT_NE(html.find("<td>0.123</td>"), std::string::npos);
  EXPECT_NE(html.find("<td>0.0321</td>"), std::string::npos);
  // Two plots: the XY plot has two lines, the error plot one.
  size_t svgs = 0, lines = 0;
  for (size_t at = html.find("<svg"); at != std::string::npos; at = html.find("<svg", at + 1))
    ++svgs;
  for (size_t at = html.find("<polyline"); at != std::string::npos;
       at = html.find("<polyline", at + 1)) {
    ++lines;
  }
  EXPECT_EQ(svgs, 2u);
  EXPECT_EQ(lines, 3u);
  EXPECT_NE(html.find("pillar &lt;3&gt;"), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);  // Self-contained, static.
}

TEST(ReportWriterTest, MissingLoopIsNullInJson) {
  ground_truth::TrajectoryScore s = MakeScore();
  s.has_loop = false;
  const std::string json = ScoreReportJson(s, ReportInfo());
  EXPECT_NE(json.find("\"loop_error_m\": null"), std::string::npos) << json;
  EXPECT_NE(ScoreReportHtml(s, ReportInfo()).find("n/a"), std::string::npos);
}

TEST(ReportWriterTest, UnwritableDirectoryIsAnError) {
  std::string error;
  EXPECT_FALSE(
      WriteScoreReport("/proc/fusemap_cannot_write_here", MakeScore(), ReportInfo(), &error));
  EXPECT_NE(error.find("/proc/fusemap_cannot_write_here"), std::string::npos) << error;
}

}  // namespace
}  // namespace io
}  // namespace fusemap
