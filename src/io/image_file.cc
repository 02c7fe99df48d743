#include "fusemap/io/image_file.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>

#include "image_header.h"
#include "write_all.h"

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
  return WriteFileAtomically(path, {{encoded.data(), encoded.size()}}, error);
}

bool ReadImageFile(const std::string& path, int flags, int max_side_px, cv::Mat* image,
                   std::string* error) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    *error = path + ": is a directory, not an image";
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    *error = path + ": cannot open";
    return false;
  }
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
  if (in.bad()) {
    *error = path + ": read error";
    return false;
  }
  ImageHeader header;
  if (!ReadImageHeader(bytes.data(), bytes.size(), &header, error)) {
    *error = path + ": " + *error;
    return false;
  }
  if (header.width > max_side_px || header.height > max_side_px) {
    *error = path + ": declares " + std::to_string(header.width) + "x" +
             std::to_string(header.height) + " pixels, more than the " +
             std::to_string(max_side_px) + " per side accepted";
    return false;
  }
  try {
    *image = cv::imdecode(bytes, flags);
  } catch (const cv::Exception& e) {
    *error = path + ": cannot decode: " + e.what();
    return false;
  }
  if (image->empty()) {
    *error = path + ": cannot decode as an image";
    return false;
  }
  return true;
}

}  // namespace io
}  // namespace fusemap
