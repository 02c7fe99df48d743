#include "vloop_common.h"

#include <cstdio>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>

namespace fusemap {
namespace vloop {

bool IntrinsicsFromList(const std::vector<double>& fx_fy_cx_cy, sensor::PinholeIntrinsics* out) {
  const std::vector<double>& v = fx_fy_cx_cy;
  if (v.size() != 4 || !(v[0] > 0.0) || !(v[1] > 0.0)) return false;
  out->fx = v[0];
  out->fy = v[1];
  out->cx = v[2];
  out->cy = v[3];
  return true;
}

std::string VocabularyPath(const std::string& given) {
  if (!given.empty()) return given;
  // build/tools/vloop/fusemap_vloop -> data/vocabulary in the source tree beside build/.
  std::error_code code;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", code);
  if (!code) {
    const std::filesystem::path beside =
        exe.parent_path() / "../../../data/vocabulary" / std::filesystem::path(FUSEMAP_DEFAULT_VOCABULARY).filename();
    if (std::filesystem::exists(beside, code)) return beside.lexically_normal().string();
  }
  return FUSEMAP_DEFAULT_VOCABULARY;
}

std::optional<visual_loop::Vocabulary> LoadVocabularyOrReport(const std::string& path) {
  std::string error;
  std::optional<visual_loop::Vocabulary> vocabulary = visual_loop::Vocabulary::Load(path, &error);
  if (!vocabulary) std::fprintf(stderr, "error: %s\n", error.c_str());
  return vocabulary;
}

cv::Mat ReadImage(const std::string& path, int flags) {
  cv::Mat image = cv::imread(path, flags);
  if (image.empty()) std::fprintf(stderr, "error: %s: cannot read image\n", path.c_str());
  return image;
}

}  // namespace vloop
}  // namespace fusemap
