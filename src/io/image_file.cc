#include "fusemap/io/image_file.h"

#include <opencv2/imgcodecs.hpp>

#include "fusemap/io/write_all.h"

namespace fusemap {
namespace io {

bool WriteImageFile(const cv::Mat& image, const std::string& path, std::string* error,
                    const std::vector<int>& params) {
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || path.find('/', dot) != std::string::npos) {
    *error = path + ": no image extension";
    return false;
  }
  // Encoded in memory, so that the file is written, checked and renamed like every output.
  std::vector<uchar> encoded;
  bool ok = false;
  try {
    ok = cv::imencode(path.substr(dot), image, encoded, params);
  } catch (const cv::Exception& e) {
    *error = path + ": " + e.what();
    return false;
  }
  if (!ok) {
    *error = path + ": cannot encode the image";
    return false;
  }
  return WriteFileAtomically(path, std::string(encoded.begin(), encoded.end()), error);
}

}  // namespace io
}  // namespace fusemap
