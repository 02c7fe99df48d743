#include "fusemap/io/loop_tables_file.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "fusemap/common/math.h"

namespace fusemap {
namespace io {
namespace {

// Fields of the next record (tab-separated if the line has a tab, so a last free-text column
// may hold spaces; else whitespace-separated), at least num_fields of them, more ignored:
// false at the end (*error empty) or with *error set; `header` receives a line starting with
// `header_word` instead of a record.
class TableReader {
 public:
  TableReader(std::istream& in, std::string origin, size_t num_fields, std::string layout,
              std::string header_word)
      : in_(in), origin_(std::move(origin)), num_fields_(num_fields), layout_(std::move(layout)),
        header_word_(std::move(header_word)) {}

  bool Next(std::vector<std::string>* fields, std::vector<std::string>* header, std::string* error) {
    std::string line;
    while (std::getline(in_, line)) {
      ++line_number_;
      Split(line, fields);
      if (fields->empty() || (*fields)[0].empty() || (*fields)[0][0] == '#') continue;
      if ((*fields)[0] == header_word_) {
        *header = *fields;
        continue;
      }
      if (fields->size() < num_fields_) {
        return Fail("expected " + std::to_string(num_fields_) + " fields (" + layout_ + "), got " +
                        std::to_string(fields->size()),
                    error);
      }
      return true;
    }
    if (in_.bad()) return Fail("read error", error);
    return false;
  }

  static void Split(const std::string& line, std::vector<std::string>* fields) {
    fields->clear();
    if (line.find('\t') == std::string::npos) {
      std::istringstream words(line);
      for (std::string word; words >> word;) fields->push_back(word);
      return;
    }
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, '\t');) fields->push_back(cell);
    if (fields->size() == 1 && (*fields)[0].find_first_not_of(" \r") == std::string::npos) fields->clear();
  }

  bool Fail(const std::string& reason, std::string* error) const {
    *error = origin_ + ":" + std::to_string(line_number_) + ": " + reason;
    return false;
  }

  bool Number(const std::string& field, const char* name, double* value, std::string* error) const {
    char* end = nullptr;
    *value = std::strtod(field.c_str(), &end);
    if (end == field.c_str() || *end != '\0' || !std::isfinite(*value)) {
      return Fail(std::string(name) + " '" + field + "' is not a finite number", error);
    }
    return true;
  }

  bool Index(const std::string& field, const char* name, int* value, std::string* error) const {
    double number = 0.0;
    if (!Number(field, name, &number, error)) return false;
    if (number < 0.0 || number > 2e9 || number != std::floor(number)) {
      return Fail(std::string(name) + " '" + field + "' is not a whole number >= 0", error);
    }
    *value = static_cast<int>(number);
    return true;
  }

 private:
  std::istream& in_;
  const std::string origin_;
  const size_t num_fields_;
  const std::string layout_;
  const std::string header_word_;
  int line_number_ = 0;
};

bool WriteText(const std::string& path, const std::string& text, std::string* error) {
  std::ofstream out(path);
  out << text;
  out.close();
  if (!out) {
    *error = path + ": write failed";
    return false;
  }
  return true;
}

template <typename Read, typename Out>
bool ReadFile(const std::string& path, Read read, Out* out, std::string* error) {
  std::ifstream in(path);
  if (!in) {
    *error = path + ": cannot open for reading";
    return false;
  }
  return read(in, path, out, error);
}

}  // namespace

bool ReadLoops(std::istream& in, const std::string& origin, std::vector<eval::LoopRecord>* loops,
               std::string* error) {
  loops->clear();
  error->clear();
  TableReader reader(in, origin, 9,
                     "node submap source laser_score visual_inliers decision x y yaw", "node");
  std::vector<std::string> f, header;
  while (reader.Next(&f, &header, error)) {
    eval::LoopRecord loop;
    double score = 0.0, inliers = 0.0, x = 0.0, y = 0.0, yaw = 0.0;
    if (!reader.Index(f[0], "node", &loop.node, error) ||
        !reader.Index(f[1], "submap", &loop.submap, error) ||
        !reader.Number(f[3], "laser_score", &score, error) ||
        !reader.Number(f[4], "visual_inliers", &inliers, error) ||
        !reader.Number(f[6], "x", &x, error) || !reader.Number(f[7], "y", &y, error) ||
        !reader.Number(f[8], "yaw", &yaw, error)) {
      return false;
    }
    if (header.size() == 9 && header[8] == "yaw_deg") yaw = common::DegToRad(yaw);
    loop.source = f[2];
    loop.laser_score = score;
    loop.visual_inliers = static_cast<int>(inliers);
    loop.decision = f[5];
    loop.T_submap_node = common::Rigid2d(x, y, yaw);
    // Files written before the column existed have none: every loop measured every way.
    const auto column = std::find(header.begin(), header.end(), "unmeasured_x");
    const size_t ux = static_cast<size_t>(column - header.begin());
    if (column != header.end() && ux + 1 < f.size() && header[ux + 1] == "unmeasured_y" &&
        (!reader.Number(f[ux], "unmeasured_x", &loop.unmeasured_direction.x(), error) ||
         !reader.Number(f[ux + 1], "unmeasured_y", &loop.unmeasured_direction.y(), error))) {
      return false;
    }
    // Likewise the turn that goes with it: files without the column slide straight.
    const auto turn = std::find(header.begin(), header.end(), "unmeasured_turn_rad_per_m");
    const size_t ut = static_cast<size_t>(turn - header.begin());
    if (turn != header.end() && ut < f.size() &&
        !reader.Number(f[ut], "unmeasured_turn_rad_per_m", &loop.unmeasured_turn_rad_per_m,
                       error)) {
      return false;
    }
    loops->push_back(loop);
  }
  return error->empty();
}

bool ReadLoopsFile(const std::string& path, std::vector<eval::LoopRecord>* loops,
                   std::string* error) {
  return ReadFile(path, ReadLoops, loops, error);
}

bool ReadSubmapAnchors(std::istream& in, const std::string& origin,
                       std::vector<eval::SubmapAnchor>* submaps, std::string* error) {
  submaps->clear();
  error->clear();
  TableReader reader(in, origin, 5, "submap first_node x y yaw", "submap");
  std::vector<std::string> f, header;
  while (reader.Next(&f, &header, error)) {
    eval::SubmapAnchor anchor;
    double x = 0.0, y = 0.0, yaw = 0.0;
    if (!reader.Index(f[0], "submap", &anchor.submap, error) ||
        !reader.Index(f[1], "first_node", &anchor.first_node, error) ||
        !reader.Number(f[2], "x", &x, error) || !reader.Number(f[3], "y", &y, error) ||
        !reader.Number(f[4], "yaw", &yaw, error)) {
      return false;
    }
    anchor.T_map_submap = common::Rigid2d(x, y, yaw);
    submaps->push_back(anchor);
  }
  return error->empty();
}

bool ReadSubmapAnchorsFile(const std::string& path, std::vector<eval::SubmapAnchor>* submaps,
                           std::string* error) {
  return ReadFile(path, ReadSubmapAnchors, submaps, error);
}

bool WriteSubmapAnchorsFile(const std::string& path, const std::vector<eval::SubmapAnchor>& submaps,
                            std::string* error) {
  std::ostringstream out;
  out << std::setprecision(9) << "submap\tfirst_node\tx\ty\tyaw\n";
  for (const eval::SubmapAnchor& s : submaps) {
    out << s.submap << '\t' << s.first_node << '\t' << s.T_map_submap.x() << '\t'
        << s.T_map_submap.y() << '\t' << s.T_map_submap.angle_rad() << '\n';
  }
  return WriteText(path, out.str(), error);
}

}  // namespace io
}  // namespace fusemap
