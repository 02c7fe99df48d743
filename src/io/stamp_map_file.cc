#include "fusemap/io/stamp_map_file.h"

#include <cstdio>
#include <utility>

#include "fusemap/io/lcm_conversions.h"
#include "numeric_line_reader.h"

namespace fusemap {
namespace io {

bool StampMapWriter::Open(const std::string& path, std::string* error) {
  path_ = path;
  out_.open(path, std::ios::out | std::ios::trunc);
  if (!out_) {
    *error = path + ": cannot open for writing";
    return false;
  }
  out_ << "# fusemap stamp map: output_s log_s log_resolution_s (one line per odometry "
          "record, file order)\n";
  return static_cast<bool>(out_);
}

bool StampMapWriter::Add(const eval::StampMapEntry& entry) {
  char line[96];
  std::snprintf(line, sizeof(line), "%.6f %.16g %.6g\n",
                static_cast<double>(StampToUtime(entry.output_s)) * 1e-6, entry.log_s,
                entry.log_resolution_s);
  out_ << line;
  return static_cast<bool>(out_);
}

bool StampMapWriter::Close(std::string* error) {
  out_.flush();
  const bool ok = static_cast<bool>(out_);
  out_.close();
  if (!ok) *error = path_ + ": write failed";
  return ok;
}

bool ReadStampMap(std::istream& in, const std::string& origin,
                  std::vector<eval::StampMapEntry>* entries, std::string* error) {
  entries->clear();
  NumericLineReader reader(in, origin, 3, "output_s log_s log_resolution_s");
  std::vector<double> v;
  while (reader.Next(&v, error)) {
    if (v[2] < 0.0) return reader.Fail("log_resolution_s is negative", error);
    if (!entries->empty() && v[0] < entries->back().output_s) {
      return reader.Fail("output_s goes backwards", error);
    }
    entries->push_back(eval::StampMapEntry{v[0], v[1], v[2]});
  }
  return error->empty();
}

bool ReadStampMapFile(const std::string& path, std::vector<eval::StampMapEntry>* entries,
                      std::string* error) {
  std::ifstream in(path);
  if (!in) {
    *error = path + ": cannot open for reading";
    return false;
  }
  return ReadStampMap(in, path, entries, error);
}

bool MapRelationsThroughStampMapFile(const std::string& path,
                                     std::vector<eval::Relation>* relations,
                                     std::string* summary, std::string* error) {
  std::vector<eval::StampMapEntry> entries;
  if (!ReadStampMapFile(path, &entries, error)) return false;
  const eval::StampMap map(std::move(entries));
  const eval::StampMapCounts counts = eval::MapRelationTimes(map, relations);
  *summary = "stamp_map: records=" + std::to_string(map.size()) +
             " stamps_exact=" + std::to_string(counts.exact) +
             " stamps_ambiguous=" + std::to_string(counts.ambiguous) +
             " stamps_unmatched=" + std::to_string(counts.unmatched);
  return true;
}

}  // namespace io
}  // namespace fusemap
