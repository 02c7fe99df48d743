#ifndef FUSEMAP_IO_REPORT_WRITER_H_
#define FUSEMAP_IO_REPORT_WRITER_H_

#include <string>
#include <vector>

#include "fusemap/ground_truth/trajectory_score.h"

namespace fusemap {
namespace io {

// What was scored, for the report's header.
struct ReportInfo {
  std::string title = "fusemap trajectory score";
  std::string gt_path;
  std::string est_path;
};

// One headline number; the HTML table and report.json are both generated from this list so
// they always carry the same figures.
struct ReportFigure {
  std::string key;    // JSON key, e.g. "ate_rmse_m".
  std::string label;  // Human label for the HTML table.
  double value = 0.0;
  std::string unit;
};

std::vector<ReportFigure> ReportFigures(const ground_truth::TrajectoryScore& score);

// report.json: {"title", "inputs", "figures": {key: value}, "tag_residuals": [...],
// "measures": [...]}; non-finite numbers are written as null.
std::string ScoreReportJson(const ground_truth::TrajectoryScore& score, const ReportInfo& info);
// A self-contained page: figures table, inline SVG of both trajectories in XY (estimate after
// the ATE alignment) and of the position error over time, per-tag and measure tables.
std::string ScoreReportHtml(const ground_truth::TrajectoryScore& score, const ReportInfo& info);

// Creates `directory` if needed and writes index.html and report.json into it.
bool WriteScoreReport(const std::string& directory, const ground_truth::TrajectoryScore& score,
                      const ReportInfo& info, std::string* error);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_REPORT_WRITER_H_
