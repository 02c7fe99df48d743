#include "fusemap/io/g2o_reader.h"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <unordered_map>
#include <vector>

#include "fusemap/pose_graph/se2_cost_function.h"

namespace fusemap {
namespace io {
namespace {

bool Fail(const std::string& origin, int line_number, const std::string& reason,
          std::string* error) {
  *error = origin + ":" + std::to_string(line_number) + ": " + reason;
  return false;
}

bool ParseInt(const std::string& token, int* value) {
  char* end = nullptr;
  errno = 0;
  const long parsed = std::strtol(token.c_str(), &end, 10);
  if (end == token.c_str() || *end != '\0' || errno == ERANGE || parsed < INT_MIN ||
      parsed > INT_MAX) {
    return false;
  }
  *value = static_cast<int>(parsed);
  return true;
}

// Beyond these a value is corrupt, not a pose graph, and the solver would overflow (a cost of
// inf): coordinates (1e9 m holds any planet-scale frame), angles, information entries.
constexpr double kMaxAbsPoseValue = 1e9;
constexpr double kMaxAbsInformation = 1e15;

// g2o tags are upper case with digits, '_' and ':' (VERTEX_SE2, EDGE_SE3:QUAT, PARAMS_...).
// Anything else is not a g2o line at all (binary or foreign data), not a tag to skip.
bool LooksLikeTag(const std::string& token) {
  if (token.empty() || token.size() > 64 || !(token[0] >= 'A' && token[0] <= 'Z')) return false;
  for (char c : token) {
    if (!((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == ':')) return false;
  }
  return true;
}

// Parses fields[first, first + count) as finite doubles of magnitude at most max_abs; on
// failure says which field and why.
bool ParseDoubles(const std::vector<std::string>& fields, size_t first, size_t count,
                  double max_abs, double* values, std::string* reason) {
  for (size_t i = 0; i < count; ++i) {
    const std::string& token = fields[first + i];
    char* end = nullptr;
    values[i] = std::strtod(token.c_str(), &end);
    if (end == token.c_str() || *end != '\0') {
      *reason = "field " + std::to_string(first + i + 1) + " '" + token + "' is not a number";
      return false;
    }
    if (!std::isfinite(values[i])) {
      *reason = "field " + std::to_string(first + i + 1) + " '" + token + "' is not finite";
      return false;
    }
    if (std::abs(values[i]) > max_abs) {
      *reason = "field " + std::to_string(first + i + 1) + " '" + token + "' is absurd (magnitude over " +
                (max_abs == kMaxAbsPoseValue ? "1e9" : "1e15") + ")";
      return false;
    }
  }
  return true;
}

struct PendingEdge {
  int line_number;
  int from_id;
  int to_id;
  pose_graph::Se2Edge edge;
};

}  // namespace

bool ReadG2o(std::istream& in, const std::string& origin, G2oFile* file, std::string* error) {
  *file = G2oFile();
  pose_graph::Se2Graph& graph = file->graph;
  std::unordered_map<int, int> index_of_id;
  std::unordered_map<int, int> line_of_id;
  std::vector<PendingEdge> edges;
  std::vector<std::pair<int, int>> fixes;  // (line, id)
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    std::istringstream stream(line);
    std::vector<std::string> fields;
    for (std::string token; stream >> token;) fields.push_back(token);
    if (fields.empty() || fields[0][0] == '#') continue;
    const std::string& tag = fields[0];
    std::string reason;
    if (tag == "VERTEX_SE2") {
      if (fields.size() != 5) {
        return Fail(origin, line_number,
                    "VERTEX_SE2 needs 4 fields 'id x y theta', got " +
                        std::to_string(fields.size() - 1), error);
      }
      int id;
      if (!ParseInt(fields[1], &id)) {
        return Fail(origin, line_number, "vertex id '" + fields[1] + "' is not an integer", error);
      }
      double pose[3];
      if (!ParseDoubles(fields, 2, 3, kMaxAbsPoseValue, pose, &reason)) {
        return Fail(origin, line_number, reason, error);
      }
      if (index_of_id.count(id)) {
        return Fail(origin, line_number, "duplicate vertex id " + std::to_string(id) +
                                             " (first at line " +
                                             std::to_string(line_of_id[id]) + ")", error);
      }
      index_of_id[id] = static_cast<int>(graph.vertices.size());
      line_of_id[id] = line_number;
      graph.vertices.emplace_back(pose[0], pose[1], pose[2]);
      graph.ids.push_back(id);
      ++file->num_vertex_lines;
    } else if (tag == "EDGE_SE2") {
      if (fields.size() != 12) {
        return Fail(origin, line_number,
                    "EDGE_SE2 needs 11 fields 'id1 id2 dx dy dtheta i11 i12 i13 i22 i23 i33', "
                    "got " + std::to_string(fields.size() - 1), error);
      }
      PendingEdge pending;
      pending.line_number = line_number;
      if (!ParseInt(fields[1], &pending.from_id) || !ParseInt(fields[2], &pending.to_id)) {
        return Fail(origin, line_number, "edge vertex ids must be integers", error);
      }
      if (pending.from_id == pending.to_id) {
        return Fail(origin, line_number, "edge from vertex " + std::to_string(pending.from_id) +
                                             " to itself", error);
      }
      double v[9];
      if (!ParseDoubles(fields, 3, 3, kMaxAbsPoseValue, v, &reason) ||
          !ParseDoubles(fields, 6, 6, kMaxAbsInformation, v + 3, &reason)) {
        return Fail(origin, line_number, reason, error);
      }
      pending.edge.T_from_to = common::Rigid2d(v[0], v[1], v[2]);
      Eigen::Matrix3d& info = pending.edge.information;
      info << v[3], v[4], v[5], v[4], v[6], v[7], v[5], v[7], v[8];
      Eigen::Matrix3d sqrt_information;
      if (!pose_graph::SqrtInformation(info, &sqrt_information)) {
        return Fail(origin, line_number, "information matrix is not positive definite", error);
      }
      edges.push_back(pending);
      ++file->num_edge_lines;
    } else if (tag == "FIX") {
      if (fields.size() < 2) return Fail(origin, line_number, "FIX needs at least one id", error);
      for (size_t i = 1; i < fields.size(); ++i) {
        int id;
        if (!ParseInt(fields[i], &id)) {
          return Fail(origin, line_number, "FIX id '" + fields[i] + "' is not an integer", error);
        }
        fixes.emplace_back(line_number, id);
      }
    } else if (LooksLikeTag(tag)) {
      ++file->skipped_tags[tag];
    } else {
      return Fail(origin, line_number, "not a g2o line (no record tag such as VERTEX_SE2)", error);
    }
  }
  if (in.bad()) return Fail(origin, line_number, "read error", error);
  if (file->num_vertex_lines == 0 && file->num_edge_lines == 0) {
    return Fail(origin, line_number, "no VERTEX_SE2 or EDGE_SE2 line: not a 2D pose graph", error);
  }

  if (graph.vertices.empty() && !edges.empty()) {
    std::set<int> ids;
    for (const PendingEdge& pending : edges) ids.insert({pending.from_id, pending.to_id});
    for (const int id : ids) {
      index_of_id[id] = static_cast<int>(graph.vertices.size());
      graph.vertices.push_back(common::Rigid2d::Identity());
      graph.ids.push_back(id);
    }
    file->vertices_from_edges = true;
  }
  for (const PendingEdge& pending : edges) {
    for (const int id : {pending.from_id, pending.to_id}) {
      if (!index_of_id.count(id)) {
        return Fail(origin, pending.line_number,
                    "edge references unknown vertex " + std::to_string(id), error);
      }
    }
    pose_graph::Se2Edge edge = pending.edge;
    edge.from = index_of_id[pending.from_id];
    edge.to = index_of_id[pending.to_id];
    graph.edges.push_back(edge);
  }
  graph.fixed.assign(graph.vertices.size(), false);
  for (const auto& [fix_line, id] : fixes) {
    if (!index_of_id.count(id)) {
      return Fail(origin, fix_line, "FIX references unknown vertex " + std::to_string(id), error);
    }
    graph.fixed[index_of_id[id]] = true;
  }
  file->num_fixed = static_cast<int>(std::count(graph.fixed.begin(), graph.fixed.end(), true));
  if (file->vertices_from_edges) file->num_initialized = pose_graph::InitializeFromEdges(&graph);
  return true;
}

bool ReadG2oFile(const std::string& path, G2oFile* file, std::string* error) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    *error = path + ": is a directory, not a g2o file";
    return false;
  }
  std::ifstream in(path);
  if (!in) {
    *error = path + ": cannot open for reading";
    return false;
  }
  return ReadG2o(in, path, file, error);
}

bool WriteG2oFile(const std::string& path, const pose_graph::Se2Graph& graph, std::string* error) {
  std::FILE* out = std::fopen(path.c_str(), "w");
  if (out == nullptr) {
    *error = path + ": cannot open for writing";
    return false;
  }
  const auto id_of = [&graph](int index) { return graph.ids.empty() ? index : graph.ids[index]; };
  for (size_t i = 0; i < graph.vertices.size(); ++i) {
    const common::Rigid2d& v = graph.vertices[i];
    std::fprintf(out, "VERTEX_SE2 %d %.17g %.17g %.17g\n", id_of(static_cast<int>(i)), v.x(),
                 v.y(), v.angle_rad());
  }
  for (size_t i = 0; i < graph.fixed.size(); ++i) {
    if (graph.fixed[i]) std::fprintf(out, "FIX %d\n", id_of(static_cast<int>(i)));
  }
  for (const pose_graph::Se2Edge& e : graph.edges) {
    const Eigen::Matrix3d& m = e.information;
    std::fprintf(out, "EDGE_SE2 %d %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n",
                 id_of(e.from), id_of(e.to), e.T_from_to.x(), e.T_from_to.y(),
                 e.T_from_to.angle_rad(), m(0, 0), m(0, 1), m(0, 2), m(1, 1), m(1, 2), m(2, 2));
  }
  const bool ok = std::fflush(out) == 0 && !std::ferror(out);
  if (std::fclose(out) != 0 || !ok) {
    *error = path + ": write failed";
    return false;
  }
  return true;
}

}  // namespace io
}  // namespace fusemap
