#include "carmen_line_parser.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace fusemap {
namespace io {
namespace {

bool Parse(std::string line, CarmenMessage* msg, std::string* reason) {
  const std::vector<char*> tokens = TokenizeCarmenLine(&line);
  return ParseCarmenMessage(tokens, true, msg, reason);
}

TEST(CarmenLineParserTest, TokenizesOnBlanks) {
  std::string line = " ODOM\t1  2\r\n";
  const std::vector<char*> tokens = TokenizeCarmenLine(&line);
  ASSERT_EQ(tokens.size(), 3u);
  EXPECT_STREQ(tokens[0], "ODOM");
  EXPECT_STREQ(tokens[2], "2");
}

TEST(CarmenLineParserTest, OdomFieldsAndWhereTheStampsWerePrinted) {
  CarmenMessage msg;
  std::string reason;
  ASSERT_TRUE(Parse("ODOM 0.5 0.25 0.1 0.3 -0.2 0 1401.34 pippo 1401.35", &msg, &reason))
      << reason;
  EXPECT_EQ(msg.type, CarmenMessageType::kOdom);
  EXPECT_DOUBLE_EQ(msg.pose[1], 0.25);
  EXPECT_DOUBLE_EQ(msg.velocity[1], -0.2);
  EXPECT_DOUBLE_EQ(msg.times[0], 1401.34);
  EXPECT_DOUBLE_EQ(msg.times[1], 1401.35);
  EXPECT_EQ(msg.time_tokens[0], 7u);
  EXPECT_EQ(msg.time_tokens[1], 9u);
}

TEST(CarmenLineParserTest, FlaserBeamsAndStampTokens) {
  CarmenMessage msg;
  std::string reason;
  ASSERT_TRUE(Parse("FLASER 3 1 2 3 4 5 0.5 0 0 0 7.25 pippo 7.5", &msg, &reason)) << reason;
  EXPECT_EQ(msg.type, CarmenMessageType::kFlaser);
  ASSERT_EQ(msg.ranges.size(), 3u);
  EXPECT_FLOAT_EQ(msg.ranges[2], 3.f);
  EXPECT_DOUBLE_EQ(msg.pose[2], 0.5);
  EXPECT_DOUBLE_EQ(msg.times[0], 7.25);
  EXPECT_EQ(msg.time_tokens[0], 11u);
  EXPECT_EQ(msg.time_tokens[1], 13u);
}

TEST(CarmenLineParserTest, MalformedLinesGiveReasons) {
  CarmenMessage msg;
  std::string reason;
  EXPECT_FALSE(Parse("ODOM 0.5 x 0.1 0.3 -0.2 0 1 pippo 1", &msg, &reason));
  EXPECT_NE(reason.find("non-numeric field 2"), std::string::npos) << reason;
  EXPECT_FALSE(Parse("ODOM 0.5 0.1 0.3 -0.2 0 1 pippo 1", &msg, &reason));
  EXPECT_NE(reason.find("expected 10 fields, found 9"), std::string::npos) << reason;
  EXPECT_FALSE(Parse("FLASER 3 1 2 nan 4 5 0.5 0 0 0 7 pippo 7", &msg, &reason));
  EXPECT_NE(reason.find("non-numeric"), std::string::npos) << reason;
}

TEST(CarmenLineParserTest, GmappingEchoAfterAScanIsAnEstimate) {
  GmappingPoseFilter filter;
  CarmenMessage scan, echo, odom;
  std::string reason;
  ASSERT_TRUE(Parse("FLASER 2 1 2 4 5 0.5 0 0 0 7 pippo 7", &scan, &reason)) << reason;
  ASSERT_TRUE(Parse("ODOM 4 5 0.5 0 0 0 7 pippo 7", &echo, &reason)) << reason;
  ASSERT_TRUE(Parse("ODOM 4 5 0.5 0 0 0 7.1 pippo 7.1", &odom, &reason)) << reason;
  EXPECT_FALSE(filter.IsEstimate("FLASER", &scan));
  EXPECT_TRUE(filter.IsEstimate("ODOM", &echo));
  // The same pose once more is no longer right after the scan.
  EXPECT_FALSE(filter.IsEstimate("ODOM", &odom));
}

}  // namespace
}  // namespace io
}  // namespace fusemap
