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

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_IMAGE_FILE_H_
