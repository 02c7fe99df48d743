#ifndef FUSEMAP_IO_LOOPS_FILE_H_
#define FUSEMAP_IO_LOOPS_FILE_H_

#include <string>
#include <vector>

#include "fusemap/visual_loop/loop_arbiter.h"

namespace fusemap {
namespace io {

// The header line of loops.tsv (tab-separated, no trailing tab).
extern const char kLoopsTsvHeader[];

// DIR/loops.tsv: the header, then one line per loop decision of the visual loop checker, in
// the order they were taken: node, submap, source (laser|visual|both), laser_score (0 without
// a laser loop), visual_inliers (0 without a verified visual loop), decision
// (laser_confirmed|visual_override|visual_forced|laser_kept|laser_rejected) and x_m, y_m,
// yaw_rad of the node in the submap by the chosen constraint (for laser_rejected, by the laser
// one that was removed); then disagreement_m and disagreement_rad between the laser and the
// visual measurement (0 unless both exist), unmeasured_x and unmeasured_y (the unit vector in
// the node's frame along which a laser match held across a corridor only measured nothing:
// x_m and y_m along it are the graph's estimate; 0 0 when it measured every way) and the
// arbiter's reason. Written atomically.
bool WriteLoopsTsv(const std::string& path,
                   const std::vector<visual_loop::ArbitrationRecord>& records, std::string* error);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_LOOPS_FILE_H_
