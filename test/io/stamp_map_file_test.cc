#include "fusemap/io/stamp_map_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "fusemap/io/carmen_reader.h"
#include "fusemap/io/relations_file.h"

namespace fusemap {
namespace io {
namespace {

std::string TempPath(const std::string& name) {
  return testing::TempDir() + "/fusemap_stamp_map_" + std::to_string(getpid()) + "_" + name;
}

std::string ReadError(const std::string& text) {
  std::istringstream in(text);
  std::vector<eval::StampMapEntry> entries;
  std::string error;
  EXPECT_FALSE(ReadStampMap(in, "x.stamps", &entries, &error)) << text;
  return error;
}

TEST(StampMapFileTest, RoundTripsThroughTheWriter) {
  const std::string path = TempPath("rt.stamps");
  StampMapWriter writer;
  std::string error;
  ASSERT_TRUE(writer.Open(path, &error)) << error;
  EXPECT_TRUE(writer.Add({1401.3366666666, 1401.34, 0.01}));
  EXPECT_TRUE(writer.Add({1401.3411, 976052857.337284, 1e-6}));
  ASSERT_TRUE(writer.Close(&error)) << error;
  std::vector<eval::StampMapEntry> entries;
  ASSERT_TRUE(ReadStampMapFile(path, &entries, &error)) << error;
  ASSERT_EQ(entries.size(), 2u);
  // Output stamps to the microsecond, as the LCM log carries them; log stamps exactly.
  EXPECT_DOUBLE_EQ(entries[0].output_s, 1401.336667);
  EXPECT_DOUBLE_EQ(entries[0].log_s, 1401.34);
  EXPECT_DOUBLE_EQ(entries[0].log_resolution_s, 0.01);
  EXPECT_DOUBLE_EQ(entries[1].log_s, 976052857.337284);
  EXPECT_DOUBLE_EQ(entries[1].log_resolution_s, 1e-6);
  std::remove(path.c_str());
}

TEST(StampMapFileTest, ErrorsNameFileAndLine) {
  EXPECT_EQ(ReadError("1 2\n"),
            "x.stamps:1: expected 3 fields 'output_s log_s log_resolution_s', got 2");
  EXPECT_EQ(ReadError("# c\n1 1 -0.01\n"), "x.stamps:2: log_resolution_s is negative");
  EXPECT_EQ(ReadError("2 2 0.01\n1 1 0.01\n"), "x.stamps:2: output_s goes backwards");
  EXPECT_NE(ReadError("1 nan 0.01\n").find("x.stamps:1:"), std::string::npos);
}

TEST(StampMapFileTest, MissingFileAndUnwritablePathAreReported) {
  std::vector<eval::StampMapEntry> entries;
  std::string error;
  EXPECT_FALSE(ReadStampMapFile("/nonexistent/x.stamps", &entries, &error));
  EXPECT_EQ(error, "/nonexistent/x.stamps: cannot open for reading");
  StampMapWriter writer;
  EXPECT_FALSE(writer.Open("/nonexistent/x.stamps", &error));
  EXPECT_EQ(error, "/nonexistent/x.stamps: cannot open for writing");
}

TEST(StampMapFileTest, MapsRelationsAndSummarises) {
  const std::string path = TempPath("map.stamps");
  std::ofstream(path) << "5.0 5.0 0.01\n5.3 6.0 0.01\n5.6 5.6 0.01\n";
  std::vector<eval::Relation> relations = {{5.001, 6.002, common::Rigid2d()}};
  std::string summary, error;
  ASSERT_TRUE(MapRelationsThroughStampMapFile(path, &relations, &summary, &error)) << error;
  EXPECT_DOUBLE_EQ(relations[0].t2_s, 5.3);
  EXPECT_EQ(summary,
            "stamp_map: records=3 stamps_exact=2 stamps_ambiguous=0 stamps_unmatched=0");
  std::remove(path.c_str());
}

TEST(StampMapFileTest, EveryIntelRelationStampFindsAnOdometryRecordIfPresent) {
  const std::string data = std::string(FUSEMAP_SHARED_DATA_DIR) + "/laser2d/";
  const std::string log_path = data + "intel.gfs.log", relations_path = data + "intel.relations";
  if (!std::ifstream(log_path).good() || !std::ifstream(relations_path).good()) {
    GTEST_SKIP() << "shared data not found: " << log_path << ", " << relations_path;
  }
  CarmenReader reader{CarmenOptions()};
  std::string error;
  ASSERT_TRUE(reader.Open(log_path, &error)) << error;
  std::vector<eval::StampMapEntry> entries;
  CarmenRecord record;
  while (reader.Next(&record, &error)) {
    if (record.kind != CarmenRecord::Kind::kOdometry) continue;
    entries.push_back({record.odometry.stamp_s, record.log_stamp_s, record.log_stamp_resolution_s});
  }
  ASSERT_TRUE(error.empty()) << error;
  std::vector<double> output_s;
  for (const eval::StampMapEntry& e : entries) output_s.push_back(e.output_s);
  std::vector<eval::Relation> relations;
  ASSERT_TRUE(ReadRelationsFile(relations_path, 976052857.337284, &relations, &error)) << error;
  const eval::StampMap map(std::move(entries));
  const eval::StampMapCounts counts = MapRelationTimes(map, &relations);
  // The data README: every relation stamp lies within 5 ms of an ODOM stamp.
  EXPECT_EQ(counts.unmatched, 0);
  EXPECT_EQ(counts.exact + counts.ambiguous, 2 * static_cast<int>(relations.size()));
  EXPECT_LT(counts.ambiguous, counts.exact / 100);
  // Each mapped stamp is an odometry record's own stamp or lies between two of a spread run.
  int far = 0;
  for (const eval::Relation& r : relations) {
    for (const double t : {r.t1_s, r.t2_s}) {
      const auto it = std::lower_bound(output_s.begin(), output_s.end(), t);
      double gap_s = INFINITY;
      if (it != output_s.end()) gap_s = *it - t;
      if (it != output_s.begin()) gap_s = std::min(gap_s, t - *(it - 1));
      if (gap_s > 0.01) ++far;
    }
  }
  EXPECT_EQ(far, 0);
}

}  // namespace
}  // namespace io
}  // namespace fusemap
