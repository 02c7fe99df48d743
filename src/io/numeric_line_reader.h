#ifndef FUSEMAP_IO_NUMERIC_LINE_READER_H_
#define FUSEMAP_IO_NUMERIC_LINE_READER_H_

#include <istream>
#include <string>
#include <vector>

namespace fusemap {
namespace io {

// Reads text records of a fixed number of whitespace-separated finite numbers, one per line,
// skipping blank lines and '#' comments (the TUM trajectory and relations formats). Every
// error is reported as `origin:line: reason`.
class NumericLineReader {
 public:
  // `field_names` is the human-readable layout used in messages, e.g. "t x y z qx qy qz qw".
  NumericLineReader(std::istream& in, std::string origin, int num_fields, std::string field_names)
      : in_(in), origin_(std::move(origin)), num_fields_(num_fields),
        field_names_(std::move(field_names)) {}

  // The next record's values. False at the end of the input (with *error empty) or on a bad
  // record or read error (with *error set).
  bool Next(std::vector<double>* values, std::string* error);

  // A failure at the current line, for checks the caller makes on a record's values.
  bool Fail(const std::string& reason, std::string* error) const;

 private:
  std::istream& in_;
  const std::string origin_;
  const int num_fields_;
  const std::string field_names_;
  int line_number_ = 0;
};

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_NUMERIC_LINE_READER_H_
