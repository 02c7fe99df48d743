#include "fusemap/mapping/adaptive_rotation_prior.h"

#include <algorithm>
#include <cmath>

#include "fusemap/common/math.h"

namespace fusemap {
namespace mapping {

void AdaptiveRotationPriorOptions::Check(common::OptionChecker* check) const {
  check->Require(weight_deg > 0.0, "weight_deg", "must be > 0");
  check->Require(min_weight >= 0.0, "min_weight", "must be >= 0");
  check->Require(max_weight >= min_weight, "max_weight", "must be >= min_weight");
  check->Require(window_scans >= 1, "window_scans", "must be >= 1");
  check->Require(min_scans >= 1 && min_scans <= window_scans, "min_scans",
                 "must be in [1, window_scans]");
}

bool AdaptiveRotationPriorOptions::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

AdaptiveRotationPriorOptions ParseAdaptiveRotationPriorOptions(common::ConfigReader& reader) {
  AdaptiveRotationPriorOptions options;
  reader.Get("enabled", &options.enabled);
  reader.Get("weight_deg", &options.weight_deg);
  reader.Get("min_weight", &options.min_weight);
  reader.Get("max_weight", &options.max_weight);
  reader.Get("window_scans", &options.window_scans);
  reader.Get("min_scans", &options.min_scans);
  reader.CheckOptions(options);
  return options;
}

AdaptiveRotationPrior::AdaptiveRotationPrior(const AdaptiveRotationPriorOptions& options)
    : options_(options) {}

void AdaptiveRotationPrior::AddCorrection(double heading_correction_rad) {
  if (!options_.enabled || !std::isfinite(heading_correction_rad)) return;
  abs_corrections_rad_.push_back(std::abs(common::NormalizeAngle(heading_correction_rad)));
  while (static_cast<int>(abs_corrections_rad_.size()) > options_.window_scans) {
    abs_corrections_rad_.pop_front();
  }
}

double AdaptiveRotationPrior::Weight(double configured_weight) const {
  if (!options_.enabled || static_cast<int>(abs_corrections_rad_.size()) < options_.min_scans) {
    return configured_weight;
  }
  const double median_deg = common::RadToDeg(common::Percentile(corrections_rad(), 0.5));
  // A median of 0 (the matches never turned the prediction) asks for the strongest prior.
  if (median_deg <= 0.0) return options_.max_weight;
  return std::clamp(options_.weight_deg / median_deg, options_.min_weight, options_.max_weight);
}

std::vector<double> AdaptiveRotationPrior::corrections_rad() const {
  return {abs_corrections_rad_.begin(), abs_corrections_rad_.end()};
}

void AdaptiveRotationPrior::Restore(const std::vector<double>& corrections_rad) {
  abs_corrections_rad_.clear();
  for (const double c : corrections_rad) AddCorrection(c);
}

}  // namespace mapping
}  // namespace fusemap
