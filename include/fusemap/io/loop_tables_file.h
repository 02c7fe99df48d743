#ifndef FUSEMAP_IO_LOOP_TABLES_FILE_H_
#define FUSEMAP_IO_LOOP_TABLES_FILE_H_

#include <istream>
#include <string>
#include <vector>

#include "fusemap/eval/loop_closure_score.h"

namespace fusemap {
namespace io {

// DIR/loops.tsv: one loop per line starting `node submap source laser_score visual_inliers
// decision x y yaw` (T_submap_node, metres and radians; a header naming the ninth column
// `yaw_deg` makes it degrees); further columns (disagreement, reason) are ignored. Tab-separated
// (a line without tabs: whitespace). '#' comments, blank lines and a header line starting with
// `node` are skipped. Errors name `origin:line: reason`.
bool ReadLoops(std::istream& in, const std::string& origin, std::vector<eval::LoopRecord>* loops,
               std::string* error);
bool ReadLoopsFile(const std::string& path, std::vector<eval::LoopRecord>* loops,
                   std::string* error);

// DIR/submaps.tsv: `submap first_node x y yaw` per line (T_map_submap, radians), same rules.
bool ReadSubmapAnchors(std::istream& in, const std::string& origin,
                       std::vector<eval::SubmapAnchor>* submaps, std::string* error);
bool ReadSubmapAnchorsFile(const std::string& path, std::vector<eval::SubmapAnchor>* submaps,
                           std::string* error);

// Writes the submaps.tsv layout (with a header line; yaw in radians, 9 significant digits).
// loops.tsv is written by io::WriteLoopsTsv (loops_file.h).
bool WriteSubmapAnchorsFile(const std::string& path, const std::vector<eval::SubmapAnchor>& submaps,
                            std::string* error);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_LOOP_TABLES_FILE_H_
