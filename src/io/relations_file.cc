#include "fusemap/io/relations_file.h"

#include <fstream>

#include "numeric_line_reader.h"

namespace fusemap {
namespace io {

bool ReadRelations(std::istream& in, const std::string& origin, double time_offset_s,
                   std::vector<eval::Relation>* relations, std::string* error) {
  relations->clear();
  NumericLineReader reader(in, origin, 8, "t1 t2 dx dy dz droll dpitch dyaw");
  std::vector<double> v;
  while (reader.Next(&v, error)) {
    if (v[0] == v[1]) return reader.Fail("t1 equals t2", error);
    relations->push_back(eval::Relation{v[0] - time_offset_s, v[1] - time_offset_s,
                                        common::Rigid2d(v[2], v[3], v[7])});
  }
  return error->empty();
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
