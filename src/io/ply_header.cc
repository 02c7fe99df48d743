#include "ply_header.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace fusemap {
namespace io {
namespace {

// A real header is a few hundred bytes; this only bounds what a corrupt one makes us read.
constexpr size_t kMaxHeaderBytes = 1 << 16;

bool Fail(const std::string& path, const std::string& reason, std::string* error) {
  *error = path + ": " + reason;
  return false;
}

// Bytes of one binary PLY scalar (PLY 1.0 type names and their sized aliases); 0 if unknown.
int TypeBytes(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" ||
      type == "float32") {
    return 4;
  }
  if (type == "double" || type == "float64") return 8;
  return 0;
}

struct Element {
  std::string name;
  uint64_t count = 0;
  uint64_t min_bytes = 0;  // per element
};

}  // namespace

bool CheckPlyFileSize(const std::string& path, std::string* error) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return Fail(path, "is a directory, not a PLY file", error);
  const uintmax_t file_size = std::filesystem::file_size(path, ec);
  if (ec) return Fail(path, "cannot read (" + ec.message() + ")", error);
  std::ifstream in(path, std::ios::binary);
  if (!in) return Fail(path, "cannot open", error);
  std::string line;
  if (!std::getline(in, line) || (line != "ply" && line != "ply\r")) return Fail(path, "not a PLY file", error);
  bool binary = false;
  std::vector<Element> elements;
  int line_number = 1;
  while (true) {
    if (static_cast<size_t>(in.tellg()) > kMaxHeaderBytes || !std::getline(in, line)) {
      return Fail(path, "PLY header has no end_header", error);
    }
    ++line_number;
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "end_header") break;
    const std::string where = "line " + std::to_string(line_number) + ": ";
    if (keyword == "format") {
      std::string format;
      words >> format;
      binary = format != "ascii";
    } else if (keyword == "element") {
      Element element;
      if (!(words >> element.name >> element.count)) return Fail(path, where + "bad element line", error);
      elements.push_back(element);
    } else if (keyword == "property") {
      if (elements.empty()) return Fail(path, where + "property before any element", error);
      std::string type;
      words >> type;
      uint64_t bytes = 2;  // ASCII: at least one character and a separator
      if (binary) {
        // A list takes at least its count (it may be empty).
        if (type == "list") words >> type;
        bytes = static_cast<uint64_t>(TypeBytes(type));
        if (bytes == 0) return Fail(path, where + "unknown property type '" + type + "'", error);
      }
      elements.back().min_bytes += bytes;
    }
  }
  const uint64_t data_bytes = file_size - static_cast<uint64_t>(in.tellg());
  uint64_t needed = 0;
  for (const Element& element : elements) {
    // Compared per element first so that count * bytes cannot overflow.
    if (element.min_bytes > 0 && element.count > data_bytes / element.min_bytes) {
      return Fail(path,
                  "header declares " + std::to_string(element.count) + " " + element.name +
                      " elements, more than the " + std::to_string(data_bytes) +
                      " data bytes after the header can hold",
                  error);
    }
    needed += element.count * element.min_bytes;
  }
  if (needed > data_bytes) {
    return Fail(path, "header declares elements of at least " + std::to_string(needed) +
                          " bytes, but only " + std::to_string(data_bytes) + " follow it",
                error);
  }
  return true;
}

}  // namespace io
}  // namespace fusemap
