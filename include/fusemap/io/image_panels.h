#ifndef FUSEMAP_IO_IMAGE_PANELS_H_
#define FUSEMAP_IO_IMAGE_PANELS_H_

#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace fusemap {
namespace io {

// Two images of the same scale (metres per pixel) side by side on white, each under its
// caption, under a title line. Both are shrunk by one common factor when together they are
// wider than max_width_px, so they keep the same scale. Text is ASCII (other characters are
// drawn as '-'). Inputs may be grey or BGR; the result is BGR.
cv::Mat SideBySide(const cv::Mat& left, const std::string& left_caption, const cv::Mat& right,
                   const std::string& right_caption, const std::string& title,
                   int max_width_px = 2400);

// Tiles images row by row, `columns` to a row, each scaled to cell_width_px wide (keeping its
// aspect ratio), on white. Empty for no images.
cv::Mat ContactSheet(const std::vector<cv::Mat>& images, int columns, int cell_width_px);

// The same from and to image files; false with a message naming the file that could not be
// read or written.
bool WriteSideBySideFile(const std::string& left_path, const std::string& left_caption,
                         const std::string& right_path, const std::string& right_caption,
                         const std::string& title, const std::string& out_path,
                         std::string* error);
bool WriteContactSheetFile(const std::vector<std::string>& paths, int columns, int cell_width_px,
                           const std::string& out_path, std::string* error);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_IMAGE_PANELS_H_
