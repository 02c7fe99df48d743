#ifndef FUSEMAP_IO_IMAGE_FILE_H_
#define FUSEMAP_IO_IMAGE_FILE_H_

#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace fusemap {
namespace io {

// cv::imwrite reports failure both by returning false and by throwing (unknown extension,
// encoder errors); this turns both into false and a message naming the path.
bool WriteImageFile(const cv::Mat& image, const std::string& path, std::string* error,
                    const std::vector<int>& params = {});

// Reads a PNG or JPEG file with cv::imdecode `flags` (cv::IMREAD_GRAYSCALE, ...), after checking
// the size its header declares against `max_side_px`: OpenCV would otherwise allocate whatever
// a corrupt header says. False with a reason naming the path for a missing file, a directory,
// another format, an absurd declared size or undecodable data.
bool ReadImageFile(const std::string& path, int flags, int max_side_px, cv::Mat* image,
                   std::string* error);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_IMAGE_FILE_H_
