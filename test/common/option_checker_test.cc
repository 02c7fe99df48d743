#include "fusemap/common/option_checker.h"

#include <gtest/gtest.h>

#include <string>

#include "fusemap/common/config_reader.h"

namespace fusemap {
namespace common {
namespace {

struct InnerOptions {
  int count = 1;
  void Check(OptionChecker* check) const { check->Require(count >= 1, "count", "must be >= 1"); }
};

struct OuterOptions {
  double rate_hz = 1.0;
  InnerOptions inner;
  void Check(OptionChecker* check) const {
    check->Require(rate_hz > 0.0, "rate_hz", "must be > 0");
    check->Nested("inner", inner);
  }
};

TEST(OptionCheckerTest, NestedProblemsCarryTheFullKeyPath) {
  OuterOptions options;
  options.rate_hz = 0.0;
  options.inner.count = 0;
  OptionChecker check;
  options.Check(&check);
  ASSERT_EQ(check.problems().size(), 2u);
  EXPECT_EQ(check.problems()[0].key, "rate_hz");
  EXPECT_EQ(check.problems()[1].key, "inner.count");
  EXPECT_EQ(check.problems()[1].message, "must be >= 1");
}

TEST(OptionCheckerTest, OwnFieldsScopeLeavesNestedStructsToTheirParsers) {
  OuterOptions options;
  options.inner.count = 0;
  OptionChecker check(OptionChecker::Scope::kOwnFields);
  options.Check(&check);
  EXPECT_TRUE(check.problems().empty());
}

TEST(OptionCheckerTest, IsValidOptionsGivesTheFirstProblemAsKeyAndReason) {
  OuterOptions options;
  EXPECT_TRUE(IsValidOptions(options, nullptr));
  options.inner.count = -3;
  std::string error;
  EXPECT_FALSE(IsValidOptions(options, &error));
  EXPECT_EQ(error, "inner.count must be >= 1");
  EXPECT_FALSE(IsValidOptions(options, nullptr));
}

// What a Parse function does: each level reports its own keys, with their lines, once.
OuterOptions ParseOuter(ConfigReader& reader) {
  OuterOptions options;
  reader.Get("rate_hz", &options.rate_hz);
  ConfigReader& inner = reader.Child("inner");
  inner.Get("count", &options.inner.count);
  inner.CheckOptions(options.inner);
  reader.CheckOptions(options);
  return options;
}

TEST(OptionCheckerTest, ConfigReaderReportsEachProblemAtItsKeyAndLine) {
  std::string error;
  auto reader = ConfigReader::FromString("rate_hz: -1\ninner:\n  count: 0\n", "o.yaml", &error);
  ASSERT_NE(reader, nullptr) << error;
  ParseOuter(*reader);
  EXPECT_FALSE(reader->Finish(&error));
  EXPECT_EQ(error,
            "o.yaml:3: key 'inner.count': must be >= 1\n"
            "o.yaml:1: key 'rate_hz': must be > 0");
}

TEST(OptionCheckerTest, AProblemWithAKeyNotInTheFileHasNoLine) {
  std::string error;
  auto reader = ConfigReader::FromString("{}\n", "o.yaml", &error);
  ASSERT_NE(reader, nullptr) << error;
  OuterOptions options;
  options.rate_hz = 0.0;  // as if another key had made the default invalid
  reader->CheckOptions(options);
  EXPECT_FALSE(reader->Finish(&error));
  EXPECT_EQ(error, "o.yaml: key 'rate_hz': must be > 0");
}

}  // namespace
}  // namespace common
}  // namespace fusemap
