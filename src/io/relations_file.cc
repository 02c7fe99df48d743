#include "fusemap/io/relations_file.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace fusemap {
namespace io {
namespace {

bool Fail(const std::string& origin, int line_number, const std::string& reason,
          std::string* error) {
  *error = origin + ":" + std::to_string(line_number) + ": " + reason;
  return false;
}

}  // namespace

bool ReadRelations(std::istream& in, const std::string& origin, double time_offset_s,
                   std::vector<eval::Relation>* relations, std::string* error) {
  relations->clear();
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    double v[8];
    int count = 0;
    std::string token;
    while (fields >> token) {
      if (count == 8) return Fail(origin, line_number, "more than 8 fields", error);
      char* end = nullptr;
      v[count] = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0') {
        return Fail(origin, line_number,
                    "field " + std::to_string(count + 1) + " '" + token + "' is not a number",
                    error);
      }
      if (!std::isfinite(v[count])) {
        return Fail(origin, line_number, "field " + std::to_string(count + 1) + " is not finite",
                    error);
      }
      ++count;
    }
    if (count != 8) {
      return Fail(
          origin, line_number,
          "expected 8 fields 't1 t2 dx dy dz droll dpitch dyaw', got " + std::to_string(count),
          error);
    }
    if (v[0] == v[1]) return Fail(origin, line_number, "t1 equals t2", error);
    relations->push_back(eval::Relation{v[0] - time_offset_s, v[1] - time_offset_s,
                                        common::Rigid2d(v[2], v[3], v[7])});
  }
  if (in.bad()) return Fail(origin, line_number, "read error", error);
  return true;
}

bool ReadRelationsFile(const std::string& path, double time_offset_s,
                       std::vector<eval::Relation>* relations, std::string* error) {
  std::ifstream in(path);
  if (!in) {
    *error = path + ": cannot open for reading";
    return false;
  }
  return ReadRelations(in, path, time_offset_s, relations, error);
}

}  // namespace io
}  // namespace fusemap
