#include "fusemap/common/config_reader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <vector>

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

// Issue 18, item 4: .inf and .nan were accepted and then hung (resolution_m: .inf, a NaN in
// T_tracking_laser) or slipped through (max_time_s: .nan).
TEST(ConfigReaderTest, NonFiniteNumbersAreErrorsNamingFileLineAndKey) {
  std::string error;
  auto reader = ConfigReader::FromString(
      "a: .inf\nsub:\n  b: .nan\n  c: -.inf\nv: [0.1, .nan, 0]\nf: .NaN\n", "cfg.yaml", &error);
  ASSERT_NE(reader, nullptr) << error;
  double a = 1.0, b = 2.0, c = 3.0;
  float f = 4.f;
  std::vector<double> v = {9.0};
  reader->Get("a", &a);
  ConfigReader& sub = reader->Child("sub");
  sub.Get("b", &b);
  sub.Get("c", &c);
  reader->Get("v", &v);
  reader->Get("f", &f);
  EXPECT_FALSE(reader->Finish(&error));
  EXPECT_EQ(a, 1.0);
  EXPECT_EQ(b, 2.0);
  EXPECT_EQ(v, std::vector<double>{9.0});
  for (const char* expected : {"cfg.yaml:1: key 'a': value must be a finite number",
                               "cfg.yaml:3: key 'sub.b'", "cfg.yaml:4: key 'sub.c'",
                               "cfg.yaml:5: key 'v'", "cfg.yaml:6: key 'f'"}) {
    EXPECT_NE(error.find(expected), std::string::npos) << expected << "\n" << error;
  }
}

// Issue 18, item 4: the second value of a repeated key was silently ignored.
TEST(ConfigReaderTest, DuplicateKeysAreRefusedAtAnyDepth) {
  std::string error;
  EXPECT_EQ(ConfigReader::FromString("a: 1\nb: 2\na: 3\n", "dup.yaml", &error), nullptr);
  EXPECT_NE(error.find("dup.yaml:3: key 'a' appears again (first on line 1)"), std::string::npos)
      << error;
  EXPECT_EQ(ConfigReader::FromString("s:\n  t:\n    x: 1\n    x: 2\n", "dup.yaml", &error), nullptr);
  EXPECT_NE(error.find("dup.yaml:4: key 's.t.x'"), std::string::npos) << error;
  // The same key in different mappings is fine.
  EXPECT_NE(ConfigReader::FromString("s:\n  x: 1\nt:\n  x: 2\n", "ok.yaml", &error), nullptr);
}

// Issue 18, item 4: --config DIR was read as an empty file, so every default applied silently.
TEST(ConfigReaderTest, DirectoryIsNotAConfigFile) {
  std::string error;
  const std::string dir = ::testing::TempDir();
  EXPECT_EQ(ConfigReader::FromFile(dir, &error), nullptr);
  EXPECT_NE(error.find("is a directory"), std::string::npos) << error;
}

}  // namespace
}  // namespace common
}  // namespace fusemap
