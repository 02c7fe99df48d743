#ifndef FUSEMAP_IO_STAMP_MAP_FILE_H_
#define FUSEMAP_IO_STAMP_MAP_FILE_H_

#include <fstream>
#include <istream>
#include <string>
#include <vector>

#include "fusemap/eval/stamp_map.h"

namespace fusemap {
namespace io {

// A stamp map file (written by fusemap_carmen2lcm --stamp-map): one line per odometry record
// in file order, `output_s log_s log_resolution_s` (seconds), '#' comments and blank lines ignored.
// Output stamps are rounded to the microsecond, as the LCM log carries them.
class StampMapWriter {
 public:
  bool Open(const std::string& path, std::string* error);
  bool Add(const eval::StampMapEntry& entry);
  // Flushes and closes; false (with *error) if any write failed.
  bool Close(std::string* error);

 private:
  std::string path_;
  std::ofstream out_;
};

// Requires three finite numbers per line, a resolution >= 0 and non-decreasing output stamps;
// errors name `origin:line: reason`.
bool ReadStampMap(std::istream& in, const std::string& origin,
                  std::vector<eval::StampMapEntry>* entries, std::string* error);
bool ReadStampMapFile(const std::string& path, std::vector<eval::StampMapEntry>* entries,
                      std::string* error);

// Reads the stamp map at `path` and moves both stamps of every relation onto its output time
// base (eval::MapRelationTimes). *summary is one line for the tools: "stamp_map: ...".
bool MapRelationsThroughStampMapFile(const std::string& path,
                                     std::vector<eval::Relation>* relations,
                                     std::string* summary, std::string* error);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_STAMP_MAP_FILE_H_
