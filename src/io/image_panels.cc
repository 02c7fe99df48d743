#include "fusemap/io/image_panels.h"

#include <algorithm>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "fusemap/io/image_file.h"

namespace fusemap {
namespace io {
namespace {

const cv::Scalar kWhite(255, 255, 255);
const cv::Scalar kBlack(0, 0, 0);
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr int kMarginPx = 10;
constexpr int kTextBandPx = 34;

cv::Mat ToBgr(const cv::Mat& image) {
  if (image.channels() == 3) return image;
  cv::Mat bgr;
  cv::cvtColor(image, bgr, image.channels() == 4 ? cv::COLOR_BGRA2BGR : cv::COLOR_GRAY2BGR);
  return bgr;
}

// Hershey fonts draw ASCII only: each UTF-8 sequence becomes one '-'.
std::string Ascii(const std::string& text) {
  std::string out;
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x80) {
      out += c;
    } else if (byte >= 0xC0) {
      out += '-';
    }
  }
  return out;
}

void PutText(cv::Mat* canvas, const std::string& text, int x, int y, double scale) {
  cv::putText(*canvas, Ascii(text), cv::Point(x, y), kFont, scale, kBlack, 1, cv::LINE_AA);
}

bool ReadImage(const std::string& path, cv::Mat* image, std::string* error) {
  *image = cv::imread(path, cv::IMREAD_COLOR);
  if (image->empty()) *error = path + ": cannot read as an image";
  return !image->empty();
}

cv::Mat Resized(const cv::Mat& image, double factor) {
  if (factor == 1.0) return image;
  cv::Mat out;
  cv::resize(image, out, cv::Size(), factor, factor, factor < 1.0 ? cv::INTER_AREA : cv::INTER_LINEAR);
  return out;
}

}  // namespace

cv::Mat SideBySide(const cv::Mat& left, const std::string& left_caption, const cv::Mat& right,
                   const std::string& right_caption, const std::string& title,
                   int max_width_px) {
  // Two pixels to spare for rounding the scaled widths.
  const double factor = std::min(1.0, static_cast<double>(max_width_px - 3 * kMarginPx - 2) /
                                          std::max(1, left.cols + right.cols));
  const cv::Mat l = Resized(ToBgr(left), factor);
  const cv::Mat r = Resized(ToBgr(right), factor);
  const int width = std::max(l.cols + r.cols + 3 * kMarginPx, 640);
  const int top = 2 * kTextBandPx;
  cv::Mat canvas(top + std::max(l.rows, r.rows) + kMarginPx, width, CV_8UC3, kWhite);
  l.copyTo(canvas(cv::Rect(kMarginPx, top, l.cols, l.rows)));
  const int right_x = 2 * kMarginPx + l.cols;
  r.copyTo(canvas(cv::Rect(right_x, top, r.cols, r.rows)));
  PutText(&canvas, title, kMarginPx, kTextBandPx - 10, 0.7);
  PutText(&canvas, left_caption, kMarginPx, top - 10, 0.55);
  PutText(&canvas, right_caption, right_x, top - 10, 0.55);
  return canvas;
}

cv::Mat ContactSheet(const std::vector<cv::Mat>& images, int columns, int cell_width_px) {
  if (images.empty() || columns < 1 || cell_width_px < 1) return cv::Mat();
  std::vector<cv::Mat> cells;
  for (const cv::Mat& image : images) {
    cells.push_back(Resized(ToBgr(image), static_cast<double>(cell_width_px) / image.cols));
  }
  const int used_columns = std::min<int>(columns, static_cast<int>(cells.size()));
  std::vector<int> row_heights;
  for (size_t i = 0; i < cells.size(); ++i) {
    if (i % columns == 0) row_heights.push_back(0);
    row_heights.back() = std::max(row_heights.back(), cells[i].rows);
  }
  int height = kMarginPx;
  for (const int h : row_heights) height += h + kMarginPx;
  cv::Mat sheet(height, kMarginPx + used_columns * (cell_width_px + kMarginPx), CV_8UC3, kWhite);
  int y = kMarginPx;
  for (size_t i = 0; i < cells.size(); ++i) {
    const int column = static_cast<int>(i % columns);
    const int x = kMarginPx + column * (cell_width_px + kMarginPx);
    cells[i].copyTo(sheet(cv::Rect(x, y, cells[i].cols, cells[i].rows)));
    if (column == columns - 1) y += row_heights[i / columns] + kMarginPx;
  }
  return sheet;
}

bool WriteSideBySideFile(const std::string& left_path, const std::string& left_caption,
                         const std::string& right_path, const std::string& right_caption,
                         const std::string& title, const std::string& out_path,
                         std::string* error) {
  cv::Mat left, right;
  return ReadImage(left_path, &left, error) && ReadImage(right_path, &right, error) &&
         WriteImageFile(SideBySide(left, left_caption, right, right_caption, title), out_path,
                        error);
}

bool WriteContactSheetFile(const std::vector<std::string>& paths, int columns, int cell_width_px,
                           const std::string& out_path, std::string* error) {
  std::vector<cv::Mat> images(paths.size());
  for (size_t i = 0; i < paths.size(); ++i) {
    if (!ReadImage(paths[i], &images[i], error)) return false;
  }
  const cv::Mat sheet = ContactSheet(images, columns, cell_width_px);
  if (sheet.empty()) {
    *error = out_path + ": nothing to draw";
    return false;
  }
  return WriteImageFile(sheet, out_path, error);
}

}  // namespace io
}  // namespace fusemap
