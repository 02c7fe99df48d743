#include "fusemap/io/image_file.h"

#include <opencv2/imgcodecs.hpp>

namespace fusemap {
namespace io {

bool WriteImageFile(const cv::Mat& image, const std::string& path, std::string* error,
                    const std::vector<int>& params) {
  bool written = false;
  try {
    written = cv::imwrite(path, image, params);
  } catch (const cv::Exception& e) {
    *error = path + ": " + e.what();
    return false;
  }
  if (!written) {
    *error = path + ": cannot write";
    return false;
  }
  return true;
}

}  // namespace io
}  // namespace fusemap
