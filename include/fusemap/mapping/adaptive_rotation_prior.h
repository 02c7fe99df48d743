#ifndef FUSEMAP_MAPPING_ADAPTIVE_ROTATION_PRIOR_H_
#define FUSEMAP_MAPPING_ADAPTIVE_ROTATION_PRIOR_H_

#include <deque>
#include <string>
#include <vector>

#include "fusemap/common/config_reader.h"

namespace fusemap {
namespace mapping {

// How strongly local SLAM's real-time correlative match is held to the predicted heading
// (its rotation_delta_cost_weight), from how far the scan matches have had to turn recent
// predictions: a robot whose odometry heading is good (a median correction of a fraction of a
// degree) keeps it where the scan alone is ambiguous (open halls, sparse outdoor returns),
// one whose odometry turns badly (several degrees per step) lets the scans decide.
struct AdaptiveRotationPriorOptions {
  bool enabled = true;
  // weight = weight_deg / (median heading correction in degrees), within [min_weight,
  // max_weight]. Chosen on the log benchmark (config/default.yaml).
  double weight_deg = 0.5;
  double min_weight = 0.1;
  double max_weight = 2.0;
  // The median is over the last window_scans corrections; until min_scans are in, the
  // configured rotation_delta_cost_weight applies.
  int window_scans = 50;
  int min_scans = 10;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

// Keys: enabled, weight_deg, min_weight, max_weight, window_scans, min_scans.
AdaptiveRotationPriorOptions ParseAdaptiveRotationPriorOptions(common::ConfigReader& reader);

class AdaptiveRotationPrior {
 public:
  explicit AdaptiveRotationPrior(const AdaptiveRotationPriorOptions& options);

  // The heading a scan match added to its prediction (matched minus predicted yaw, any sign).
  void AddCorrection(double heading_correction_rad);
  // The rotation_delta_cost_weight for the next match: `configured_weight` while disabled or
  // before min_scans corrections.
  double Weight(double configured_weight) const;

  // The sizes (>= 0) of the corrections held, oldest first (for checkpoints).
  std::vector<double> corrections_rad() const;
  void Restore(const std::vector<double>& corrections_rad);

 private:
  AdaptiveRotationPriorOptions options_;
  std::deque<double> abs_corrections_rad_;
};

}  // namespace mapping
}  // namespace fusemap

#endif  // FUSEMAP_MAPPING_ADAPTIVE_ROTATION_PRIOR_H_
