#ifndef FUSEMAP_IO_RELATIONS_FILE_H_
#define FUSEMAP_IO_RELATIONS_FILE_H_

#include <istream>
#include <string>
#include <vector>

#include "fusemap/eval/relation_error.h"

namespace fusemap {
namespace io {

// Ground-truth relations of Kümmerle et al. (2009): one per line,
// `t1 t2 dx dy dz droll dpitch dyaw` (seconds, metres, radians), '#' comments and blank lines
// ignored. time_offset_s is subtracted from both stamps, mapping absolute relation stamps onto
// a log's time base. dz, droll and dpitch must be finite but are dropped: the metric is planar.
// Requires exactly 8 finite numbers and t2 != t1; errors name `origin:line: reason`.
bool ReadRelations(std::istream& in, const std::string& origin, double time_offset_s,
                   std::vector<eval::Relation>* relations, std::string* error);
bool ReadRelationsFile(const std::string& path, double time_offset_s,
                       std::vector<eval::Relation>* relations, std::string* error);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_RELATIONS_FILE_H_
