#include "fusemap/mapping/deflated_cells.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace fusemap {
namespace mapping {
namespace {

// Every 16-bit value, the extremes included, comes back exactly.
TEST(DeflatedCellsTest, RoundTripIsLossless) {
  std::vector<uint16_t> cells(70000);
  for (size_t i = 0; i < cells.size(); ++i) cells[i] = static_cast<uint16_t>(i * 7919u);
  cells[0] = 0;
  cells[1] = 0xffff;
  std::vector<uint8_t> deflated;
  ASSERT_TRUE(DeflateCells(cells, &deflated));
  std::vector<uint16_t> inflated;
  ASSERT_TRUE(InflateCells(deflated, cells.size(), &inflated));
  EXPECT_EQ(inflated, cells);

  ASSERT_TRUE(DeflateCells({}, &deflated));
  ASSERT_TRUE(InflateCells(deflated, 0, &inflated));
  EXPECT_TRUE(inflated.empty());
}

// A grid of unknown and saturated free cells, as outdoors, deflates to a small fraction.
TEST(DeflatedCellsTest, MostlyUniformGridTakesLittle) {
  std::vector<uint16_t> cells(1000 * 1000, 0);
  for (size_t i = 0; i < cells.size(); i += 3) cells[i] = 1000;
  std::vector<uint8_t> deflated;
  ASSERT_TRUE(DeflateCells(cells, &deflated));
  EXPECT_LT(deflated.size(), cells.size() * sizeof(uint16_t) / 50);
}

// Bytes that are not what DeflateCells made for that many cells are refused, not misread.
TEST(DeflatedCellsTest, WrongCountOrCorruptDataIsRefused) {
  const std::vector<uint16_t> cells(5000, 1234);
  std::vector<uint8_t> deflated;
  ASSERT_TRUE(DeflateCells(cells, &deflated));
  std::vector<uint16_t> inflated;
  EXPECT_FALSE(InflateCells(deflated, cells.size() + 1, &inflated));
  EXPECT_FALSE(InflateCells(deflated, cells.size() - 1, &inflated));
  std::vector<uint8_t> truncated(deflated.begin(), deflated.begin() + deflated.size() / 2);
  EXPECT_FALSE(InflateCells(truncated, cells.size(), &inflated));
  EXPECT_FALSE(InflateCells({1, 2, 3, 4}, cells.size(), &inflated));
}

}  // namespace
}  // namespace mapping
}  // namespace fusemap
