#include "lcm_wire.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

namespace fusemap {
namespace io {
namespace lcm_wire {
namespace {

void PutInt32(int32_t value, std::vector<uint8_t>* bytes) {
  for (int shift = 24; shift >= 0; shift -= 8) {
    bytes->push_back(static_cast<uint8_t>(static_cast<uint32_t>(value) >> shift));
  }
}

TEST(LcmWireTest, ReadsBigEndianAndStopsAtTheEnd) {
  const std::vector<uint8_t> bytes = {0, 0, 0, 0, 0, 0, 1, 2, 0xff, 0xff, 0xff, 0xfe};
  WireCursor cursor(bytes.data(), static_cast<int>(bytes.size()));
  int64_t word = 0;
  int32_t small = 0;
  ASSERT_TRUE(cursor.ReadInt64(&word));
  EXPECT_EQ(word, 258);
  ASSERT_TRUE(cursor.ReadInt32(&small));
  EXPECT_EQ(small, -2);
  EXPECT_TRUE(cursor.AtEnd(nullptr));
  EXPECT_FALSE(cursor.ReadInt32(&small));
  EXPECT_FALSE(cursor.Skip(1));
}

TEST(LcmWireTest, NullDataIsEmpty) {
  WireCursor cursor(nullptr, 100);
  int32_t value = 0;
  EXPECT_FALSE(cursor.ReadInt32(&value));
  EXPECT_TRUE(cursor.AtEnd(nullptr));
}

TEST(LcmWireTest, StringsNeedTheirTerminatorAndAllTheirBytes) {
  std::vector<uint8_t> bytes;
  PutInt32(3, &bytes);
  bytes.insert(bytes.end(), {'a', 'b', 0});
  EXPECT_TRUE(WireCursor(bytes.data(), static_cast<int>(bytes.size())).SkipString());
  EXPECT_FALSE(WireCursor(bytes.data(), static_cast<int>(bytes.size()) - 1).SkipString());

  std::vector<uint8_t> empty;
  PutInt32(0, &empty);  // Not even the terminator: no LCM encoder writes this.
  EXPECT_FALSE(WireCursor(empty.data(), static_cast<int>(empty.size())).SkipString());
  EXPECT_TRUE(WireCursor(empty.data(), static_cast<int>(empty.size())).SkipBytes());

  std::vector<uint8_t> negative;
  PutInt32(-5, &negative);
  EXPECT_FALSE(WireCursor(negative.data(), static_cast<int>(negative.size())).SkipBytes());
}

TEST(LcmWireTest, TrailingBytesAreNamed) {
  const std::vector<uint8_t> bytes = {1, 2, 3};
  WireCursor cursor(bytes.data(), static_cast<int>(bytes.size()));
  std::string error;
  EXPECT_FALSE(cursor.AtEnd(&error));
  EXPECT_EQ(error, "3 trailing bytes after message");
}

}  // namespace
}  // namespace lcm_wire
}  // namespace io
}  // namespace fusemap
