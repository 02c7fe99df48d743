#ifndef FUSEMAP_IO_G2O_READER_H_
#define FUSEMAP_IO_G2O_READER_H_

#include <istream>
#include <map>
#include <string>

#include "fusemap/pose_graph/se2_graph.h"

namespace fusemap {
namespace io {

// A 2D pose graph read from g2o's text format.
struct G2oFile {
  // Vertices in file order with their g2o ids in graph.ids; edges by vertex index.
  pose_graph::Se2Graph graph;
  int num_vertex_lines = 0;
  int num_edge_lines = 0;
  int num_fixed = 0;
  // Lines with tags this reader does not handle (VERTEX_XY, EDGE_SE2_XY, ...) are skipped and
  // counted here by tag, so the caller can say what was ignored.
  std::map<std::string, int> skipped_tags;
  // True if the file had no VERTEX_SE2 lines (e.g. the Olson CSAIL/manhattan sets): vertices
  // were created for every id in an edge, in ascending id order, and their poses composed from
  // the edges with pose_graph::InitializeFromEdges; num_initialized of them were reached.
  bool vertices_from_edges = false;
  int num_initialized = 0;
};

// Reads `VERTEX_SE2 id x y theta`, `EDGE_SE2 id1 id2 dx dy dtheta i11 i12 i13 i22 i23 i33` (the
// upper triangle of the information matrix over x, y, theta) and `FIX id...`, in any order.
// Blank lines and lines starting with '#' are ignored; unknown tags are skipped and counted.
// Fails with `origin:line: reason` on a line without a tag-like first word (binary or foreign
// data), a file with neither VERTEX_SE2 nor EDGE_SE2, a missing or extra field, a non-numeric,
// non-finite or absurd field (a coordinate or angle over 1e9, information over 1e15), a
// duplicate vertex id, an edge or FIX naming an unknown vertex, an edge from a vertex
// to itself, or an information matrix that is not positive definite.
bool ReadG2o(std::istream& in, const std::string& origin, G2oFile* file, std::string* error);
bool ReadG2oFile(const std::string& path, G2oFile* file, std::string* error);

// Writes VERTEX_SE2 (ids from graph.ids, or indices if empty), FIX and EDGE_SE2 lines with
// enough digits to round-trip.
bool WriteG2oFile(const std::string& path, const pose_graph::Se2Graph& graph, std::string* error);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_G2O_READER_H_
