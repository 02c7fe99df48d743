#include "fusemap/common/config_reader.h"

#include <gtest/gtest.h>

namespace fusemap {
namespace common {
namespace {

TEST(ConfigReaderTest, ReadsValuesAndKeepsDefaults) {
  std::string error;
  auto reader = ConfigReader::FromString("a: 2.5\nsub:\n  n: 3\n", "test.yaml", &error);
  ASSERT_NE(reader, nullptr) << error;
  double a = 1.0, b = 7.0;
  int n = 0;
  reader->Get("a", &a);
  reader->Get("b", &b);
  reader->Child("sub").Get("n", &n);
  EXPECT_TRUE(reader->Finish(&error)) << error;
  EXPECT_EQ(a, 2.5);
  EXPECT_EQ(b, 7.0);
  EXPECT_EQ(n, 3);
}

TEST(ConfigReaderTest, UnknownKeyIsAnErrorNamingFileLineAndKey) {
  std::string error;
  auto reader = ConfigReader::FromString("a: 1\nsub:\n  typo_key: 3\n", "robot.yaml", &error);
  ASSERT_NE(reader, nullptr);
  double a = 0;
  reader->Get("a", &a);
  reader->Child("sub");
  EXPECT_FALSE(reader->Finish(&error));
  EXPECT_NE(error.find("robot.yaml:3"), std::string::npos) << error;
  EXPECT_NE(error.find("sub.typo_key"), std::string::npos) << error;
}

TEST(ConfigReaderTest, WrongTypeIsAnError) {
  std::string error;
  auto reader = ConfigReader::FromString("n: hello\n", "x.yaml", &error);
  ASSERT_NE(reader, nullptr);
  int n = 5;
  reader->Get("n", &n);
  EXPECT_FALSE(reader->Finish(&error));
  EXPECT_EQ(n, 5);
  EXPECT_NE(error.find("'n'"), std::string::npos) << error;
}

TEST(ConfigReaderTest, SyntaxErrorAndMissingFileAreReported) {
  std::string error;
  EXPECT_EQ(ConfigReader::FromString("a: [1, 2\n", "bad.yaml", &error), nullptr);
  EXPECT_NE(error.find("bad.yaml"), std::string::npos);
  EXPECT_EQ(ConfigReader::FromFile("/nonexistent/x.yaml", &error), nullptr);
  EXPECT_NE(error.find("/nonexistent/x.yaml"), std::string::npos);
}

}  // namespace
}  // namespace common
}  // namespace fusemap
