#include "fusemap/io/g2o_reader.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <random>
#include <sstream>

#include "fusemap/common/math.h"

namespace fusemap {
namespace io {
namespace {

constexpr char kSmallGraph[] =
    "# a triangle\n"
    "VERTEX_SE2 10 0 0 0\n"
    "VERTEX_SE2 11 1.0 0.1 1.5707963\n"
    "\n"
    "EDGE_SE2 10 11 1 0 1.5707963 100 0 0 100 0 400\n"
    "EDGE_SE2 11 12 1 0 1.5707963 100 10 0 100 0 400\n"
    "EDGE_SE2 10 12 1 1 3.1415926 100 0 0 100 0 400\n"
    "VERTEX_SE2 12 1.0 1.0 3.0\n"
    "VERTEX_XY 99 1 2\n"
    "EDGE_SE2_XY 10 99 1 2 1 0 1\n"
    "FIX 10\n";

bool Read(const std::string& text, G2oFile* file, std::string* error) {
  std::istringstream in(text);
  return ReadG2o(in, "graph.g2o", file, error);
}

TEST(G2oReaderTest, ParsesVerticesEdgesAndFix) {
  G2oFile file;
  std::string error;
  ASSERT_TRUE(Read(kSmallGraph, &file, &error)) << error;
  const pose_graph::Se2Graph& graph = file.graph;
  ASSERT_EQ(graph.vertices.size(), 3u);
  EXPECT_EQ(graph.ids, (std::vector<int>{10, 11, 12}));
  EXPECT_NEAR(graph.vertices[1].y(), 0.1, 1e-12);
  EXPECT_NEAR(graph.vertices[2].angle_rad(), 3.0, 1e-12);
  ASSERT_EQ(graph.edges.size(), 3u);
  EXPECT_EQ(graph.edges[1].from, 1);
  EXPECT_EQ(graph.edges[1].to, 2);  // vertex 12 was defined after the edge
  EXPECT_EQ(graph.edges[1].information(0, 1), 10.0);
  EXPECT_EQ(graph.edges[1].information(1, 0), 10.0);
  EXPECT_EQ(graph.edges[1].information(2, 2), 400.0);
  EXPECT_EQ(graph.fixed, (std::vector<bool>{true, false, false}));
  EXPECT_EQ(file.num_fixed, 1);
  EXPECT_EQ(file.skipped_tags.at("VERTEX_XY"), 1);
  EXPECT_EQ(file.skipped_tags.at("EDGE_SE2_XY"), 1);
  EXPECT_FALSE(file.vertices_from_edges);
}

TEST(G2oReaderTest, EdgeOnlyFileGetsPosesFromOdometry) {
  G2oFile file;
  std::string error;
  ASSERT_TRUE(Read("EDGE_SE2 0 1 1 0 0 1 0 0 1 0 1\n"
                   "EDGE_SE2 1 2 1 0 1.5707963267948966 1 0 0 1 0 1\n"
                   "EDGE_SE2 2 0 5 5 0 1 0 0 1 0 1\n",
                   &file, &error))
      << error;
  EXPECT_TRUE(file.vertices_from_edges);
  EXPECT_EQ(file.num_initialized, 3);
  ASSERT_EQ(file.graph.vertices.size(), 3u);
  EXPECT_NEAR(file.graph.vertices[2].x(), 2.0, 1e-12);
  EXPECT_NEAR(file.graph.vertices[2].angle_rad(), common::kPi / 2, 1e-12);
}

TEST(G2oReaderTest, EachErrorNamesFileAndLine) {
  const struct {
    std::string text;
    std::string expected;
  } cases[] = {
      {"VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 0 0\n", "graph.g2o:2: VERTEX_SE2 needs 4 fields"},
      {"VERTEX_SE2 0 0 0 0 7\n", "graph.g2o:1: VERTEX_SE2 needs 4 fields"},
      {"VERTEX_SE2 x 0 0 0\n", "graph.g2o:1: vertex id 'x' is not an integer"},
      {"VERTEX_SE2 0 0 abc 0\n", "graph.g2o:1: field 4 'abc' is not a number"},
      {"VERTEX_SE2 0 0 0 nan\n", "graph.g2o:1: field 5 'nan' is not finite"},
      {"VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 0 0 0\n\nVERTEX_SE2 0 1 1 1\n",
       "graph.g2o:4: duplicate vertex id 0 (first at line 1)"},
      {"VERTEX_SE2 0 0 0 0\nEDGE_SE2 0 1 1 0 0 1 0 0 1 0\n", "graph.g2o:2: EDGE_SE2 needs 11"},
      {"VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 0 0 0\nEDGE_SE2 0 1 1 0 inf 1 0 0 1 0 1\n",
       "graph.g2o:3: field 6 'inf' is not finite"},
      {"VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 0 0 0\nEDGE_SE2 0 1 1 0 0 1 2 0 1 0 1\n",
       "graph.g2o:3: information matrix is not positive definite"},
      {"VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 0 0 0\nEDGE_SE2 0 0 1 0 0 1 0 0 1 0 1\n",
       "graph.g2o:3: edge from vertex 0 to itself"},
      {"VERTEX_SE2 0 0 0 0\nEDGE_SE2 0 5 1 0 0 1 0 0 1 0 1\nVERTEX_SE2 1 0 0 0\n",
       "graph.g2o:2: edge references unknown vertex 5"},
      {"VERTEX_SE2 0 0 0 0\nFIX 3\n", "graph.g2o:2: FIX references unknown vertex 3"},
      {"VERTEX_SE2 0 0 0 0\nFIX\n", "graph.g2o:2: FIX needs at least one id"},
  };
  for (const auto& c : cases) {
    G2oFile file;
    std::string error;
    EXPECT_FALSE(Read(c.text, &file, &error)) << c.text;
    EXPECT_EQ(error.rfind(c.expected, 0), 0u) << "got: " << error << "\nwanted: " << c.expected;
  }
}

// Issue 18, item 14: random bytes were read as a graph of skipped tags and optimised to exit 0;
// values of 1e300 ran to final_cost=inf. Both are now errors naming file and line.
TEST(G2oReaderTest, RandomBytesAndAbsurdValuesAreRefused) {
  const struct {
    std::string text;
    std::string expected;
  } cases[] = {
      {"", "graph.g2o:0: no VERTEX_SE2 or EDGE_SE2 line"},
      {"# only a comment\nVERTEX_XY 1 2 3\n", "graph.g2o:2: no VERTEX_SE2 or EDGE_SE2 line"},
      {"VERTEX_SE2 0 0 0 0\n\x89PNG\x01\x02 7\n", "graph.g2o:2: not a g2o line"},
      {"vertex_se2 0 0 0 0\n", "graph.g2o:1: not a g2o line"},
      {"VERTEX_SE2 0 1e300 0 0\n", "graph.g2o:1: field 3 '1e300' is absurd"},
      {"VERTEX_SE2 0 0 0 -2e9\n", "graph.g2o:1: field 5 '-2e9' is absurd"},
      {"VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 0 0 0\nEDGE_SE2 0 1 1e300 0 0 1 0 0 1 0 1\n",
       "graph.g2o:3: field 4 '1e300' is absurd"},
      {"VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 0 0 0\nEDGE_SE2 0 1 1 0 0 1e300 0 0 1 0 1\n",
       "graph.g2o:3: field 7 '1e300' is absurd"},
  };
  for (const auto& c : cases) {
    G2oFile file;
    std::string error;
    EXPECT_FALSE(Read(c.text, &file, &error)) << c.text;
    EXPECT_EQ(error.rfind(c.expected, 0), 0u) << "got: " << error << "\nwanted: " << c.expected;
  }
  // Random bytes with a fixed seed: always refused.
  std::mt19937 rng(18);
  for (int trial = 0; trial < 200; ++trial) {
    std::string junk(1 + rng() % 2000, '\0');
    for (char& c : junk) c = static_cast<char>(rng());
    G2oFile file;
    std::string error;
    EXPECT_FALSE(Read(junk, &file, &error)) << trial;
    EXPECT_EQ(error.rfind("graph.g2o:", 0), 0u) << error;
  }
  G2oFile file;
  std::string error;
  EXPECT_FALSE(ReadG2oFile(::testing::TempDir(), &file, &error));
  EXPECT_NE(error.find("is a directory"), std::string::npos) << error;
}

TEST(G2oReaderTest, WriteThenReadRoundTrips) {
  G2oFile file;
  std::string error;
  ASSERT_TRUE(Read(kSmallGraph, &file, &error)) << error;
  const std::string path =
      (std::filesystem::temp_directory_path() / "fusemap_g2o_reader_test.g2o").string();
  ASSERT_TRUE(WriteG2oFile(path, file.graph, &error)) << error;
  G2oFile again;
  ASSERT_TRUE(ReadG2oFile(path, &again, &error)) << error;
  std::remove(path.c_str());
  ASSERT_EQ(again.graph.vertices.size(), 3u);
  EXPECT_EQ(again.graph.ids, file.graph.ids);
  EXPECT_EQ(again.graph.fixed, file.graph.fixed);
  EXPECT_EQ(again.graph.vertices[1].y(), file.graph.vertices[1].y());
  ASSERT_EQ(again.graph.edges.size(), 3u);
  EXPECT_EQ(again.graph.edges[1].information, file.graph.edges[1].information);
  EXPECT_EQ(again.graph.edges[2].T_from_to.angle_rad(), file.graph.edges[2].T_from_to.angle_rad());
}

TEST(G2oReaderTest, OptimisesMitDataset) {
  const std::string path = std::string(FUSEMAP_SHARED_DATA_DIR) + "/pose_graphs/MIT.g2o";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not found (shared data absent)";
  G2oFile file;
  std::string error;
  ASSERT_TRUE(ReadG2oFile(path, &file, &error)) << error;
  EXPECT_EQ(file.graph.vertices.size(), 808u);
  EXPECT_EQ(file.graph.edges.size(), 827u);
  for (pose_graph::Se2Edge& edge : file.graph.edges) edge.robust = true;
  pose_graph::OptimizationOptions options;
  options.huber_scale = 1.0;
  options.max_num_iterations = 200;
  const pose_graph::OptimizationSummary summary =
      pose_graph::SolveSe2GraphRobustThenPlain(options, &file.graph);
  // Initial cost 2.2e9; the optimum, reached from several starts, is 20.58.
  EXPECT_LT(summary.final_cost, 1e-6 * summary.initial_cost);
  EXPECT_NEAR(summary.final_cost, 20.58, 0.1);
  EXPECT_TRUE(summary.converged);
}

}  // namespace
}  // namespace io
}  // namespace fusemap
