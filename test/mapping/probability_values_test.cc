#include "fusemap/mapping/probability_values.h"

#include <gtest/gtest.h>

namespace fusemap {
namespace mapping {
namespace {

// One quantisation step of the 15-bit value is 0.8 / 32766 ~ 2.4e-5.
constexpr float kValueTol = 1e-4f;

float Apply(const std::vector<uint16_t>& table, uint16_t* value) {
  *value = table[*value] & static_cast<uint16_t>(~kUpdateMarker);
  return ValueToProbability(*value);
}

TEST(ProbabilityValuesTest, ValueRoundTripWithinQuantisation) {
  for (float p = kMinProbability; p <= kMaxProbability; p += 0.01f) {
    EXPECT_NEAR(ValueToProbability(ProbabilityToValue(p)), p, kValueTol);
  }
  EXPECT_EQ(ProbabilityToValue(kMinProbability), 1);
  EXPECT_EQ(ProbabilityToValue(kMaxProbability), kMaxValue);
  EXPECT_EQ(ProbabilityToValue(0.f), 1);  // clamped
  EXPECT_EQ(ProbabilityToValue(1.f), kMaxValue);
}

TEST(ProbabilityValuesTest, UnknownCellTakesObservationProbability) {
  for (float p : {0.55f, 0.49f, 0.7f, 0.2f}) {
    const auto table = ComputeLookupTableToApplyOdds(Odds(p));
    uint16_t value = kUnknownValue;
    EXPECT_NEAR(Apply(table, &value), p, kValueTol) << p;
  }
}

TEST(ProbabilityValuesTest, TableEntriesCarryTheUpdateMarker) {
  const auto table = ComputeLookupTableToApplyOdds(Odds(0.55f));
  EXPECT_EQ(table.size(), 2u * (kMaxValue + 1));
  for (int v = 0; v <= kMaxValue; v += 97) EXPECT_TRUE(table[v] & kUpdateMarker) << v;
}

TEST(ProbabilityValuesTest, OneUpdateMultipliesOdds) {
  // Hess et al. 2016, eq. 2: odds(0.55) * odds(0.55) -> p = 0.5990.
  const auto table = ComputeLookupTableToApplyOdds(Odds(0.55f));
  uint16_t value = ProbabilityToValue(0.55f);
  const float expected = ProbabilityFromOdds(Odds(0.55f) * Odds(0.55f));
  EXPECT_NEAR(Apply(table, &value), expected, kValueTol);
}

TEST(ProbabilityValuesTest, RepeatedHitsClampAtMaxAndMissesAtMin) {
  const auto hit = ComputeLookupTableToApplyOdds(Odds(0.55f));
  const auto miss = ComputeLookupTableToApplyOdds(Odds(0.49f));
  uint16_t value = kUnknownValue;
  float previous = 0.f;
  for (int i = 0; i < 200; ++i) {
    const float p = Apply(hit, &value);
    EXPECT_GE(p, previous - 1e-6f);
    previous = p;
  }
  EXPECT_NEAR(previous, kMaxProbability, kValueTol);
  EXPECT_EQ(value, kMaxValue);
  for (int i = 0; i < 2000; ++i) Apply(miss, &value);
  EXPECT_NEAR(ValueToProbability(value), kMinProbability, kValueTol);
  EXPECT_EQ(value, 1);  // known, at the floor
}

TEST(ProbabilityValuesTest, ValueToProbabilityTableReadsUnknownAsGiven) {
  const std::vector<float> table = ComputeValueToProbabilityTable(0.5f);
  ASSERT_EQ(table.size(), static_cast<size_t>(kMaxValue) + 1);
  EXPECT_EQ(table[kUnknownValue], 0.5f);
  for (int value = 1; value <= kMaxValue; ++value) {
    ASSERT_EQ(table[value], ValueToProbability(static_cast<uint16_t>(value))) << value;
  }
}

}  // namespace
}  // namespace mapping
}  // namespace fusemap
