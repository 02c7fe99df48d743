#include "fusemap/io/loops_file.h"

#include <cstdio>

#include "write_all.h"

namespace fusemap {
namespace io {

const char kLoopsTsvHeader[] =
    "node\tsubmap\tsource\tlaser_score\tvisual_inliers\tdecision\tx_m\ty_m\tyaw_rad\t"
    "disagreement_m\tdisagreement_rad\tunmeasured_x\tunmeasured_y\tunmeasured_turn_rad_per_m\t"
    "reason";

bool WriteLoopsTsv(const std::string& path,
                   const std::vector<visual_loop::ArbitrationRecord>& records, std::string* error) {
  std::string text = std::string(kLoopsTsvHeader) + "\n";
  for (const visual_loop::ArbitrationRecord& r : records) {
    const visual_loop::LoopMeasurement2D* shown =
        r.chosen ? &*r.chosen : (r.laser ? &*r.laser : (r.visual ? &*r.visual : nullptr));
    const common::Rigid2d pose = shown ? shown->T_submap_node : common::Rigid2d::Identity();
    const Eigen::Vector2d unmeasured =
        shown ? shown->unmeasured_direction : Eigen::Vector2d::Zero();
    const double unmeasured_turn = shown ? shown->unmeasured_turn_rad_per_m : 0.0;
    char line[352];
    std::snprintf(line, sizeof(line),
                  "%d\t%d\t%s\t%.4f\t%d\t%s\t%.4f\t%.4f\t%.5f\t%.4f\t%.5f\t%.4f\t%.4f\t%.5f\t",
                  r.node, r.submap, visual_loop::ToString(r.source),
                  r.laser ? r.laser->laser_score : 0.0, r.visual ? r.visual->visual_inliers : 0,
                  visual_loop::ToString(r.decision), pose.translation().x(), pose.translation().y(),
                  pose.angle_rad(), r.translation_disagreement_m, r.rotation_disagreement_rad,
                  unmeasured.x(), unmeasured.y(), unmeasured_turn);
    // The reason is free text: tabs and newlines would break the columns.
    std::string reason = r.reason;
    for (char& c : reason) {
      if (c == '\t' || c == '\n') c = ' ';
    }
    text += line + reason + "\n";
  }
  return WriteFileAtomically(path, text, error);
}

}  // namespace io
}  // namespace fusemap
