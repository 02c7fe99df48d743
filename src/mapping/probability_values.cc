#include "fusemap/mapping/probability_values.h"

#include <algorithm>
#include <cmath>

namespace fusemap {
namespace mapping {

uint16_t ProbabilityToValue(float probability) {
  const float p = std::clamp(probability, kMinProbability, kMaxProbability);
  const float scaled = (p - kMinProbability) / (kMaxProbability - kMinProbability);
  return static_cast<uint16_t>(1 + std::lround(scaled * (kMaxValue - 1)));
}

float ValueToProbability(uint16_t value) {
  value &= static_cast<uint16_t>(~kUpdateMarker);
  if (value == kUnknownValue) return kMinProbability;
  return kMinProbability +
         (kMaxProbability - kMinProbability) * static_cast<float>(value - 1) / (kMaxValue - 1);
}

std::vector<float> ComputeValueToProbabilityTable(float unknown_probability) {
  std::vector<float> table(kMaxValue + 1);
  table[kUnknownValue] = unknown_probability;
  for (int value = 1; value <= kMaxValue; ++value) {
    table[value] = ValueToProbability(static_cast<uint16_t>(value));
  }
  return table;
}

std::vector<uint16_t> ComputeLookupTableToApplyOdds(float odds) {
  std::vector<uint16_t> table(2 * (kMaxValue + 1), 0);
  // First observation of an unknown cell takes the observation's probability itself.
  table[kUnknownValue] = ProbabilityToValue(ProbabilityFromOdds(odds)) | kUpdateMarker;
  for (int value = 1; value <= kMaxValue; ++value) {
    const float updated =
        ProbabilityFromOdds(Odds(ValueToProbability(static_cast<uint16_t>(value))) * odds);
    table[value] = ProbabilityToValue(updated) | kUpdateMarker;
  }
  return table;
}

}  // namespace mapping
}  // namespace fusemap
