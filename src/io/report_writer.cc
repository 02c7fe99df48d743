#include "fusemap/io/report_writer.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>

namespace fusemap {
namespace io {
namespace {

// Plots keep at most this many vertices per line; the page stays small for long runs.
constexpr size_t kMaxPlotPoints = 2000;

std::string Number(double value) {
  if (!std::isfinite(value)) return "null";
  std::ostringstream out;
  out << std::setprecision(9) << value;
  return out.str();
}

std::string Escape(const std::string& text, bool html) {
  std::string out;
  for (char c : text) {
    if (html && c == '<')
      out += "&lt;";
    else if (html && c == '>')
      out += "&gt;";
    else if (html && c == '&')
      out += "&amp;";
    else if (c == '"')
      out += html ? "&quot;" : "\\\"";
    else if (!html && c == '\\')
      out += "\\\\";
    else if (!html && static_cast<unsigned char>(c) < 0x20)
      out += ' ';
    else
      out += c;
  }
  return out;
}

std::string Json(const std::string& text) { return "\"" + Escape(text, false) + "\""; }
std::string Html(const std::string& text) { return Escape(text, true); }

std::string StatsJson(const eval::ErrorStatistics& s) {
  return "{\"count\": " + std::to_string(s.count) + ", \"mean\": " + Number(s.mean) +
         ", \"std\": " + Number(s.std) + ", \"rmse\": " + Number(s.rmse) +
         ", \"median\": " + Number(s.median) + ", \"max\": " + Number(s.max) + "}";
}

// Maps data coordinates into an SVG box (y up), optionally with equal scale on both axes.
struct PlotFrame {
  double x0, x1, y0, y1;
  double width, height, margin;
  double X(double x) const { return margin + (x - x0) / (x1 - x0) * (width - 2 * margin); }
  double Y(double y) const {
    return height - margin - (y - y0) / (y1 - y0) * (height - 2 * margin);
  }
};

PlotFrame MakeFrame(const std::vector<Eigen::Vector2d>& points, bool equal_aspect) {
  PlotFrame f{0, 1, 0, 1, 640, 420, 40};
  if (!points.empty()) {
    f.x0 = f.x1 = points[0].x();
    f.y0 = f.y1 = points[0].y();
    for (const auto& p : points) {
      f.x0 = std::min(f.x0, p.x()), f.x1 = std::max(f.x1, p.x());
      f.y0 = std::min(f.y0, p.y()), f.y1 = std::max(f.y1, p.y());
    }
  }
  if (f.x1 - f.x0 < 1e-9) f.x0 -= 0.5, f.x1 += 0.5;
  if (f.y1 - f.y0 < 1e-9) f.y0 -= 0.5, f.y1 += 0.5;
  if (equal_aspect) {
    const double sx = (f.x1 - f.x0) / (f.width - 2 * f.margin);
    const double sy = (f.y1 - f.y0) / (f.height - 2 * f.margin);
    const double s = std::max(sx, sy);
    const double cx = 0.5 * (f.x0 + f.x1), cy = 0.5 * (f.y0 + f.y1);
    f.x0 = cx - 0.5 * s * (f.width - 2 * f.margin), f.x1 = cx + 0.5 * s * (f.width - 2 * f.margin);
    f.y0 = cy - 0.5 * s * (f.height - 2 * f.margin),
    f.y1 = cy + 0.5 * s * (f.height - 2 * f.margin);
  }
  return f;
}

std::string Polyline(const PlotFrame& f, const std::vector<Eigen::Vector2d>& points,
                     const std::string& colour) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(1) << "<polyline fill=\"none\" stroke=\"" << colour
      << "\" stroke-width=\"1.5\" points=\"";
  const size_t step = std::max<size_t>(1, points.size() / kMaxPlotPoints);
  for (size_t i = 0; i < points.size(); i += step) {
    out << f.X(points[i].x()) << ',' << f.Y(points[i].y()) << ' ';
  }
  if (!points.empty()) out << f.X(points.back().x()) << ',' << f.Y(points.back().y());
  out << "\"/>\n";
  return out.str();
}

std::string Svg(const PlotFrame& f, const std::string& body, const std::string& x_label,
                const std::string& y_label) {
  std::ostringstream out;
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << f.width << "\" height=\""
      << f.height << "\" style=\"border:1px solid #ccc;background:#fff\">\n"
      << "<text x=\"" << f.margin << "\" y=\"" << f.height - 8 << "\" font-size=\"12\">"
      << Html(x_label) << ": " << Number(f.x0) << " .. " << Number(f.x1) << "</text>\n"
      << "<text x=\"4\" y=\"16\" font-size=\"12\">" << Html(y_label) << ": " << Number(f.y0)
      << " .. " << Number(f.y1) << "</text>\n"
      << body << "</svg>\n";
  return out.str();
}

}  // namespace

std::vector<ReportFigure> ReportFigures(const ground_truth::TrajectoryScore& s) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  return {
      {"gt_poses", "Ground-truth poses", static_cast<double>(s.gt_poses), ""},
      {"est_poses", "Estimated poses", static_cast<double>(s.est_poses), ""},
      {"associated_poses", "Associated pose pairs", static_cast<double>(s.associated), ""},
      {"gt_length_m", "Ground-truth path length", s.gt_length_m, "m"},
      {"ate_rmse_m", "ATE RMSE (aligned)", s.ate.trans_m.rmse, "m"},
      {"ate_mean_m", "ATE mean (aligned)", s.ate.trans_m.mean, "m"},
      {"ate_max_m", "ATE max (aligned)", s.ate.trans_m.max, "m"},
      {"ate_unaligned_rmse_m", "ATE RMSE (no alignment)", s.ate.unaligned_rmse_m, "m"},
      {"rpe_trans_rmse_m", "RPE translation RMSE per segment", s.rpe.trans_m.rmse, "m"},
      {"rpe_rot_rmse_deg", "RPE rotation RMSE per segment", s.rpe.rot_deg.rmse, "deg"},
      {"rpe_trans_per_m", "RPE translation per metre travelled", s.rpe_trans_per_m, "m/m"},
      {"loop_error_m", "Start-end error at loop closure", s.has_loop ? s.loop_error_m : nan, "m"},
      {"loop_end_s", "Loop closure instant", s.has_loop ? s.loop_end_s : nan, "s"},
  };
}

std::string ScoreReportJson(const ground_truth::TrajectoryScore& s, const ReportInfo& info) {
  std::ostringstream out;
  out << "{\n  \"title\": " << Json(info.title)
      << ",\n  \"inputs\": {\"gt\": " << Json(info.gt_path) << ", \"est\": " << Json(info.est_path)
      << "},\n  \"figures\": {";
  const auto figures = ReportFigures(s);
  for (size_t i = 0; i < figures.size(); ++i) {
    out << (i ? ",\n" : "\n") << "    " << Json(figures[i].key) << ": " << Number(figures[i].value);
  }
  out << "\n  },\n  \"ate_m\": " << StatsJson(s.ate.trans_m) << ",\n  \"tag_residuals\": [";
  for (size_t i = 0; i < s.tag_residuals.size(); ++i) {
    out << (i ? ",\n" : "\n") << "    {\"tag_id\": " << s.tag_residuals[i].tag_id
        << ", \"position_error_m\": " << StatsJson(s.tag_residuals[i].position_error_m) << "}";
  }
  out << "\n  ],\n  \"measures\": [";
  for (size_t i = 0; i < s.measures.size(); ++i) {
    const auto& m = s.measures[i];
    out << (i ? ",\n" : "\n") << "    {\"from\": " << Json(m.from) << ", \"to\": " << Json(m.to)
        << ", \"measured_m\": " << Number(m.measured_m) << ", \"map_m\": " << Number(m.map_m)
        << ", \"error_m\": " << Number(m.error_m) << "}";
  }
  out << "\n  ]\n}\n";
  return out.str();
}

std::string ScoreReportHtml(const ground_truth::TrajectoryScore& s, const ReportInfo& info) {
  std::ostringstream out;
  out << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" << Html(info.title)
      << "</title>\n<style>body{font-family:sans-serif;margin:2em}table{border-collapse:collapse}"
         "td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}"
         "td:first-child{text-align:left}</style></head><body>\n"
      << "<h1>" << Html(info.title) << "</h1>\n<p>Ground truth: <code>" << Html(info.gt_path)
      << "</code><br>Estimate: <code>" << Html(info.est_path) << "</code></p>\n"
      << "<h2>Figures</h2>\n<table id=\"figures\"><tr><th>Figure</th><th>Value</th><th>Unit</th>"
         "</tr>\n";
  for (const ReportFigure& f : ReportFigures(s)) {
    out << "<tr data-key=\"" << f.key << "\"><td>" << Html(f.label) << "</td><td>"
        << (std::isfinite(f.value) ? Number(f.value) : "n/a") << "</td><td>" << f.unit
        << "</td></tr>\n";
  }
  out << "</table>\n<h2>Trajectories (XY)</h2>\n<p><span style=\"color:#1f77b4\">ground truth"
         "</span>, <span style=\"color:#d62728\">estimate (aligned)</span></p>\n";
  std::vector<Eigen::Vector2d> gt_xy, est_xy, error_t;
  for (size_t i = 0; i < s.gt_positions.size(); ++i) {
    gt_xy.push_back(s.gt_positions[i].head<2>());
    est_xy.push_back(s.est_positions_aligned[i].head<2>());
    error_t.emplace_back(s.stamps_s[i] - s.stamps_s.front(), s.position_errors_m[i]);
  }
  std::vector<Eigen::Vector2d> both = gt_xy;
  both.insert(both.end(), est_xy.begin(), est_xy.end());
  const PlotFrame xy = MakeFrame(both, true);
  out << Svg(xy, Polyline(xy, gt_xy, "#1f77b4") + Polyline(xy, est_xy, "#d62728"), "x [m]",
             "y [m]");
  error_t.emplace_back(error_t.empty() ? 0.0 : error_t.front().x(), 0.0);  // Axis from zero.
  const PlotFrame et = MakeFrame(error_t, false);
  error_t.pop_back();
  out << "<h2>Position error over time</h2>\n"
      << Svg(et, Polyline(et, error_t, "#d62728"), "time since start [s]", "error [m]");
  out << "<h2>Per-tag residuals</h2>\n<table><tr><th>Tag</th><th>Sightings</th><th>Mean [m]</th>"
         "<th>RMSE [m]</th><th>Max [m]</th></tr>\n";
  for (const auto& r : s.tag_residuals) {
    out << "<tr><td>" << r.tag_id << "</td><td>" << r.position_error_m.count << "</td><td>"
        << Number(r.position_error_m.mean) << "</td><td>" << Number(r.position_error_m.rmse)
        << "</td><td>" << Number(r.position_error_m.max) << "</td></tr>\n";
  }
  out << "</table>\n<h2>Map measures</h2>\n<table><tr><th>From</th><th>To</th><th>Measured [m]"
         "</th><th>Map [m]</th><th>Error [m]</th></tr>\n";
  for (const auto& m : s.measures) {
    out << "<tr><td>" << Html(m.from) << "</td><td>" << Html(m.to) << "</td><td>"
        << Number(m.measured_m) << "</td><td>" << Number(m.map_m) << "</td><td>"
        << Number(m.error_m) << "</td></tr>\n";
  }
  out << "</table>\n</body></html>\n";
  return out.str();
}

bool WriteScoreReport(const std::string& directory, const ground_truth::TrajectoryScore& score,
                      const ReportInfo& info, std::string* error) {
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec) {
    *error = directory + ": cannot create directory: " + ec.message();
    return false;
  }
  const std::pair<std::string, std::string> files[] = {
      {directory + "/index.html", ScoreReportHtml(score, info)},
      {directory + "/report.json", ScoreReportJson(score, info)}};
  for (const auto& [path, text] : files) {
    std::ofstream out(path);
    out << text;
    if (!out.good()) {
      *error = path + ": cannot write file";
      return false;
    }
  }
  return true;
}

}  // namespace io
}  // namespace fusemap
