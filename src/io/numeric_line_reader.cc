#include "numeric_line_reader.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

namespace fusemap {
namespace io {

bool NumericLineReader::Fail(const std::string& reason, std::string* error) const {
  *error = origin_ + ":" + std::to_string(line_number_) + ": " + reason;
  return false;
}

bool NumericLineReader::Next(std::vector<double>* values, std::string* error) {
  error->clear();
  std::string line;
  while (std::getline(in_, line)) {
    ++line_number_;
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    values->clear();
    std::string token;
    while (fields >> token) {
      const int index = static_cast<int>(values->size());
      if (index == num_fields_) {
        return Fail("more than " + std::to_string(num_fields_) + " fields", error);
      }
      char* end = nullptr;
      const double v = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0') {
        return Fail("field " + std::to_string(index + 1) + " '" + token + "' is not a number",
                    error);
      }
      if (!std::isfinite(v)) {
        return Fail("field " + std::to_string(index + 1) + " is not finite", error);
      }
      values->push_back(v);
    }
    if (static_cast<int>(values->size()) != num_fields_) {
      return Fail("expected " + std::to_string(num_fields_) + " fields '" + field_names_ +
                      "', got " + std::to_string(values->size()),
                  error);
    }
    return true;
  }
  if (in_.bad()) return Fail("read error", error);
  return false;
}

}  // namespace io
}  // namespace fusemap
