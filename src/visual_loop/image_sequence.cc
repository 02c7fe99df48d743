#include "fusemap/visual_loop/image_sequence.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <set>

namespace fusemap {
namespace visual_loop {

bool NaturalLess(const std::string& a, const std::string& b) {
  size_t i = 0;
  size_t j = 0;
  const auto is_digit = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; };
  while (i < a.size() && j < b.size()) {
    if (is_digit(a[i]) && is_digit(b[j])) {
      size_t ei = i;
      size_t ej = j;
      while (ei < a.size() && is_digit(a[ei])) ++ei;
      while (ej < b.size() && is_digit(b[ej])) ++ej;
      // Compare as numbers without overflow: strip leading zeros, then length, then digits.
      size_t si = i;
      size_t sj = j;
      while (si + 1 < ei && a[si] == '0') ++si;
      while (sj + 1 < ej && b[sj] == '0') ++sj;
      if (ei - si != ej - sj) return ei - si < ej - sj;
      const int order = a.compare(si, ei - si, b, sj, ej - sj);
      if (order != 0) return order < 0;
      // Equal numbers: the one written with fewer digits (no leading zeros) first.
      if (ei - i != ej - j) return ei - i < ej - j;
      i = ei;
      j = ej;
      continue;
    }
    if (a[i] != b[j]) return static_cast<unsigned char>(a[i]) < static_cast<unsigned char>(b[j]);
    ++i;
    ++j;
  }
  return a.size() - i < b.size() - j;
}

std::vector<std::string> ListImages(const std::string& directory, std::string* error) {
  static const std::set<std::string> kExtensions = {".png", ".jpg", ".jpeg", ".pgm", ".ppm", ".bmp"};
  std::vector<std::string> names;
  std::error_code code;
  std::filesystem::directory_iterator it(directory, code);
  if (code) {
    *error = directory + ": " + code.message();
    return {};
  }
  for (const auto& entry : it) {
    if (!entry.is_regular_file()) continue;
    std::string extension = entry.path().extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (kExtensions.count(extension) != 0) names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end(), NaturalLess);
  std::vector<std::string> paths;
  for (const std::string& name : names) paths.push_back((std::filesystem::path(directory) / name).string());
  return paths;
}

}  // namespace visual_loop
}  // namespace fusemap
