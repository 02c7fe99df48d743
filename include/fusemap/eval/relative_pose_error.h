#ifndef FUSEMAP_EVAL_RELATIVE_POSE_ERROR_H_
#define FUSEMAP_EVAL_RELATIVE_POSE_ERROR_H_

#include <string>

#include "fusemap/common/config_reader.h"
#include "fusemap/eval/error_statistics.h"
#include "fusemap/eval/trajectory.h"

namespace fusemap {
namespace eval {

enum class DeltaUnit { kMetres, kSeconds };

struct RpeOptions {
  double delta = 1.0;  // In delta_unit.
  DeltaUnit delta_unit = DeltaUnit::kMetres;
  double max_time_diff_s = 0.02;  // Association of estimated to ground-truth poses.

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

// Keys: delta, delta_unit ("m" or "s"), max_time_diff_s.
RpeOptions ParseRpeOptions(common::ConfigReader& reader);

// Relative pose error of Sturm et al. (2012), Sec. VI-A, eq. 1:
// E_i = (Q_i^-1 Q_{i+Δ})^-1 (P_i^-1 P_{i+Δ}) with Q ground truth and P the estimate, over all
// associated poses i. Δ is a time interval or a distance travelled; for metres the distance is
// measured along the ground truth (unlike the TUM script, which uses the estimate) so that
// estimate noise does not shorten the pairs. j is the associated pose whose index (time or
// distance) is closest to index_i + Δ, j > i; pairs whose target lies past the end are dropped.
struct RpeResult {
  ErrorStatistics trans_m;  // |trans(E_i)|.
  ErrorStatistics rot_deg;  // Angle of rot(E_i).
};

RpeResult ComputeRpe(const Trajectory& gt, const Trajectory& est, const RpeOptions& options);

}  // namespace eval
}  // namespace fusemap

#endif  // FUSEMAP_EVAL_RELATIVE_POSE_ERROR_H_
