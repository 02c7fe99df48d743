#include "vloop_common.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include <opencv2/imgcodecs.hpp>

namespace fusemap {
namespace vloop {

std::optional<std::string> Arguments::Get(const std::string& name) const {
  for (const auto& [key, value] : options) {
    if (key == name) return value;
  }
  return std::nullopt;
}

bool ParseArguments(int argc, char** argv, int first, const std::vector<std::string>& with_value,
                    const std::vector<std::string>& flags, Arguments* out, std::string* error) {
  for (int i = first; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      out->help = true;
    } else if (std::find(with_value.begin(), with_value.end(), arg) != with_value.end()) {
      if (i + 1 >= argc) {
        *error = arg + " needs a value";
        return false;
      }
      out->options.emplace_back(arg, argv[++i]);
    } else if (std::find(flags.begin(), flags.end(), arg) != flags.end()) {
      out->options.emplace_back(arg, "");
    } else if (arg.size() > 1 && arg[0] == '-') {
      *error = "unknown option '" + arg + "'";
      return false;
    } else {
      out->positional.push_back(arg);
    }
  }
  return true;
}

bool ParseDouble(const std::string& text, double* out) {
  char* end = nullptr;
  *out = std::strtod(text.c_str(), &end);
  return !text.empty() && end != nullptr && *end == '\0';
}

bool ParseInt(const std::string& text, int* out) {
  char* end = nullptr;
  const long value = std::strtol(text.c_str(), &end, 10);
  *out = static_cast<int>(value);
  return !text.empty() && *end == '\0' && value >= -1000000000 && value <= 1000000000;
}

bool ParseIntrinsics(const std::string& text, sensor::PinholeIntrinsics* out) {
  std::stringstream stream(text);
  std::string field;
  std::vector<double> values;
  while (std::getline(stream, field, ',')) {
    double value;
    if (!ParseDouble(field, &value)) return false;
    values.push_back(value);
  }
  if (values.size() != 4 || !(values[0] > 0.0) || !(values[1] > 0.0)) return false;
  out->fx = values[0];
  out->fy = values[1];
  out->cx = values[2];
  out->cy = values[3];
  return true;
}

std::string VocabularyPath(const Arguments& arguments) {
  if (const auto path = arguments.Get("--vocabulary")) return *path;
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
