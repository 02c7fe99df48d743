#include "fusemap/io/relations_file.h"

#include <gtest/gtest.h>

#include <sstream>

namespace fusemap {
namespace io {
namespace {

std::string ReadError(const std::string& text) {
  std::istringstream in(text);
  std::vector<eval::Relation> relations;
  std::string error;
  EXPECT_FALSE(ReadRelations(in, "x.relations", 0.0, &relations, &error)) << text;
  return error;
}

TEST(RelationsFileTest, ParsesAndSubtractsOffset) {
  std::istringstream in(
      "# comment\n"
      "976052905.167303 976052911.885496 -0.056990 -0.128430 0.000000 0.000000 0.000000 -1.682210\n"
      "\n"
      "976052911.885496 976052913.712702 0.332780 -0.005920 0 0 0 -0.019150\n");
  std::vector<eval::Relation> relations;
  std::string error;
  ASSERT_TRUE(ReadRelations(in, "x.relations", 976052857.337284, &relations, &error)) << error;
  ASSERT_EQ(relations.size(), 2u);
  EXPECT_NEAR(relations[0].t1_s, 47.830019, 1e-6);
  EXPECT_NEAR(relations[0].t2_s, 54.548212, 1e-6);
  EXPECT_DOUBLE_EQ(relations[0].T_1_2.x(), -0.056990);
  EXPECT_DOUBLE_EQ(relations[0].T_1_2.y(), -0.128430);
  EXPECT_DOUBLE_EQ(relations[0].T_1_2.angle_rad(), -1.682210);
  EXPECT_DOUBLE_EQ(relations[1].T_1_2.angle_rad(), -0.019150);
}

TEST(RelationsFileTest, ErrorsNameFileAndLine) {
  EXPECT_EQ(ReadError("1 2 0 0 0 0 0\n"),
            "x.relations:1: expected 8 fields 't1 t2 dx dy dz droll dpitch dyaw', got 7");
  EXPECT_EQ(ReadError("\n1 2 0 0 0 0 0 0 0\n"), "x.relations:2: more than 8 fields");
  EXPECT_EQ(ReadError("1 2 0 0 zero 0 0 0\n"), "x.relations:1: field 5 'zero' is not a number");
  EXPECT_EQ(ReadError("1 2 0 0 0 0 0 inf\n"), "x.relations:1: field 8 is not finite");
  EXPECT_EQ(ReadError("1 2 0 0 0 0 0 0\n3 3 0 0 0 0 0 0\n"), "x.relations:2: t1 equals t2");
}

TEST(RelationsFileTest, MissingFile) {
  std::vector<eval::Relation> relations;
  std::string error;
  EXPECT_FALSE(ReadRelationsFile("/nonexistent/r.relations", 0.0, &relations, &error));
  EXPECT_EQ(error, "/nonexistent/r.relations: cannot open for reading");
}

TEST(RelationsFileTest, ReadsSharedIntelRelations) {
  const std::string path = std::string(FUSEMAP_SHARED_DATA_DIR) + "/laser2d/intel.relations";
  std::vector<eval::Relation> relations;
  std::string error;
  if (!ReadRelationsFile(path, 976052857.337284, &relations, &error)) {
    GTEST_SKIP() << "shared data not available (" << error << ")";
  }
  EXPECT_EQ(relations.size(), 2984u);
  for (const eval::Relation& r : relations) {
    ASSERT_GT(r.t1_s, 0.0);
    ASSERT_LT(r.t2_s, 2700.0);
  }
}

}  // namespace
}  // namespace io
}  // namespace fusemap
