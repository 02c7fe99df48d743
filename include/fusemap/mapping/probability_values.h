#ifndef FUSEMAP_MAPPING_PROBABILITY_VALUES_H_
#define FUSEMAP_MAPPING_PROBABILITY_VALUES_H_

#include <cstdint>
#include <vector>

namespace fusemap {
namespace mapping {

// Occupancy probabilities are stored as 15-bit integers so that an odds update is one table
// look-up (Hess et al. 2016, eq. 2: M_new = clamp(odds^-1(odds(M_old) * odds(p_hit)))).
// Value 0 means "unknown"; bit 15 marks a cell already updated by the current range data, so
// a cell crossed by several rays of one scan is updated once.
constexpr float kMinProbability = 0.1f;
constexpr float kMaxProbability = 0.9f;
constexpr uint16_t kUnknownValue = 0;
constexpr uint16_t kUpdateMarker = 1u << 15;
constexpr uint16_t kMaxValue = 32767;

inline float Odds(float probability) { return probability / (1.f - probability); }
inline float ProbabilityFromOdds(float odds) { return odds / (odds + 1.f); }

// Maps a probability in [kMinProbability, kMaxProbability] to a value in [1, kMaxValue].
uint16_t ProbabilityToValue(float probability);
// Inverse of ProbabilityToValue; kUnknownValue maps to kMinProbability, the value the scan
// matchers assume for cells never observed.
float ValueToProbability(uint16_t value);
// ValueToProbability for every stored value (bit 15 masked off by the caller), except that
// kUnknownValue maps to `unknown_probability`: a scan matcher scores millions of cells per
// scan, and one load is much cheaper than the conversion. Size kMaxValue + 1.
std::vector<float> ComputeValueToProbabilityTable(float unknown_probability);

// Table indexed by the current stored value (unknown included) giving the value after one
// observation with the given odds, with kUpdateMarker set. Entries for marked values are
// unused. Size 2 * (kMaxValue + 1).
std::vector<uint16_t> ComputeLookupTableToApplyOdds(float odds);

}  // namespace mapping
}  // namespace fusemap

#endif  // FUSEMAP_MAPPING_PROBABILITY_VALUES_H_
