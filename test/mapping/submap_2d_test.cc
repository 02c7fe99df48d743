#include "fusemap/mapping/submap_2d.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace fusemap {
namespace mapping {
namespace {

// A short scan: the robot at `origin` sees one wall point 1 m ahead.
sensor::RangeData OneReturn(const Eigen::Vector2f& origin) {
  sensor::RangeData data;
  data.origin = origin;
  data.returns = {origin + Eigen::Vector2f(1.f, 0.f)};
  return data;
}

TEST(Submap2DTest, StartsWithA100CellBoxCentredOnItsOrigin) {
  const Submap2D submap(Eigen::Vector2f(3.f, -2.f), 0.05);
  const MapLimits limits = submap.grid()->limits();
  EXPECT_EQ(limits.num_x_cells, 100);
  EXPECT_EQ(limits.num_y_cells, 100);
  EXPECT_NEAR(limits.resolution_m, 0.05, 1e-12);
  EXPECT_NEAR(limits.origin_m.x(), 0.5, 1e-9);
  EXPECT_NEAR(limits.origin_m.y(), -4.5, 1e-9);
  EXPECT_NEAR(submap.T_local_submap().x(), 3.0, 1e-6);
  EXPECT_NEAR(submap.T_local_submap().y(), -2.0, 1e-6);
  EXPECT_NEAR(submap.T_local_submap().angle_rad(), 0.0, 1e-12);
  EXPECT_EQ(submap.num_range_data(), 0);
  EXPECT_FALSE(submap.finished());
}

TEST(Submap2DTest, InsertsInLocalCoordinates) {
  Submap2D submap(Eigen::Vector2f(3.f, -2.f), 0.05);
  const RangeDataInserter2D inserter{ProbabilityGridRangeDataInserterOptions()};
  submap.InsertRangeData(OneReturn(Eigen::Vector2f(3.f, -2.f)), inserter);
  EXPECT_EQ(submap.num_range_data(), 1);
  const std::shared_ptr<const ProbabilityGrid> grid = submap.grid();
  const MapLimits& limits = grid->limits();
  EXPECT_NEAR(grid->GetProbability(limits.GetCellIndex(Eigen::Vector2f(4.f, -2.f))), 0.55f, 1e-4f);
  EXPECT_NEAR(grid->GetProbability(limits.GetCellIndex(Eigen::Vector2f(3.5f, -2.f))), 0.49f, 1e-4f);
}

// Global SLAM keeps finished submaps deflated: the same cells come back, in far less memory,
// and a grid handed out before compaction stays valid.
TEST(Submap2DTest, CompactedSubmapKeepsItsCellsInLessMemory) {
  Submap2D submap(Eigen::Vector2f(0.f, 0.f), 0.05);
  const RangeDataInserter2D inserter{ProbabilityGridRangeDataInserterOptions()};
  for (int i = 0; i < 20; ++i) {
    sensor::RangeData data;
    data.origin = Eigen::Vector2f(0.1f * i, 0.f);
    for (int beam = 0; beam < 360; ++beam) {
      const float angle_rad = beam * 3.14159265f / 180.f;
      data.returns.push_back(data.origin + 8.f * Eigen::Vector2f(std::cos(angle_rad), std::sin(angle_rad)));
    }
    submap.InsertRangeData(data, inserter);
  }
  submap.Finish();
  const std::shared_ptr<const ProbabilityGrid> before = submap.grid();
  const size_t inflated_bytes = submap.grid_bytes();
  EXPECT_FALSE(submap.compacted());

  submap.Compact();
  ASSERT_TRUE(submap.compacted());
  EXPECT_LT(submap.grid_bytes() * 3, inflated_bytes);
  const std::shared_ptr<const ProbabilityGrid> after = submap.grid();
  EXPECT_NE(after.get(), before.get());
  EXPECT_EQ(after->limits().num_x_cells, before->limits().num_x_cells);
  EXPECT_EQ(after->limits().num_y_cells, before->limits().num_y_cells);
  EXPECT_EQ(after->limits().origin_m, before->limits().origin_m);
  EXPECT_EQ(after->cells(), before->cells());
  Eigen::Array2i min_before, max_before, min_after, max_after;
  ASSERT_TRUE(before->ComputeKnownBounds(&min_before, &max_before));
  ASSERT_TRUE(after->ComputeKnownBounds(&min_after, &max_after));
  EXPECT_TRUE((min_before == min_after).all() && (max_before == max_after).all());
  // A checkpoint of a compacted submap is the same as of the inflated one.
  EXPECT_EQ(submap.ExportState().cells, before->cells());
  submap.Compact();  // again: nothing to do
  EXPECT_TRUE(submap.compacted());
}

TEST(ActiveSubmaps2DTest, FinishesSubmapsInOrderWithTwiceNumRangeData) {
  constexpr int kN = 5;
  SubmapsOptions options;
  options.num_range_data = kN;
  ActiveSubmaps2D active(options);
  EXPECT_TRUE(active.submaps().empty());

  std::vector<std::shared_ptr<const Submap2D>> finished;  // in the order they finished
  std::vector<std::shared_ptr<const Submap2D>> all;
  for (int i = 1; i <= 3 * kN; ++i) {
    const Eigen::Vector2f origin(0.1f * i, 0.f);
    const auto inserted = active.InsertRangeData(OneReturn(origin));
    ASSERT_FALSE(inserted.empty());
    ASSERT_LE(inserted.size(), 2u);
    EXPECT_EQ(inserted.size(), i <= kN ? 1u : 2u) << i;
    for (const auto& submap : inserted) {
      if (std::find(all.begin(), all.end(), submap) == all.end()) {
        all.push_back(submap);
        // A new submap starts at the origin of the range data that created it.
        EXPECT_NEAR(submap->T_local_submap().x(), origin.x(), 1e-6) << i;
      }
      if (submap->finished() && std::find(finished.begin(), finished.end(), submap) ==
                                    finished.end()) {
        finished.push_back(submap);
        EXPECT_EQ(submap->num_range_data(), 2 * kN);
        EXPECT_EQ(i % kN, 0) << i;
      }
    }
    // Only the front one can be finished; the back one never is.
    EXPECT_FALSE(inserted.back()->finished() && inserted.size() == 2) << i;
  }
  // Submaps started at inserts 1, N + 1, 2N + 1; the first two finished at 2N and 3N.
  ASSERT_EQ(all.size(), 3u);
  EXPECT_NEAR(all[0]->T_local_submap().x(), 0.1, 1e-6);
  EXPECT_NEAR(all[1]->T_local_submap().x(), 0.1 * (kN + 1), 1e-6);
  EXPECT_NEAR(all[2]->T_local_submap().x(), 0.1 * (2 * kN + 1), 1e-6);
  ASSERT_EQ(finished.size(), 2u);
  EXPECT_EQ(finished[0], all[0]);
  EXPECT_EQ(finished[1], all[1]);
  EXPECT_EQ(all[2]->num_range_data(), kN);
  EXPECT_FALSE(all[2]->finished());

  // The finished front stays listed until the next insertion drops it.
  const auto now = active.submaps();
  ASSERT_EQ(now.size(), 2u);
  EXPECT_EQ(now[0], all[1]);
  EXPECT_EQ(now[1], all[2]);
  const auto next = active.InsertRangeData(OneReturn(Eigen::Vector2f(5.f, 0.f)));
  ASSERT_EQ(next.size(), 2u);
  EXPECT_EQ(next[0], all[2]);
  EXPECT_EQ(next[0]->num_range_data(), kN + 1);
  EXPECT_EQ(next[1]->num_range_data(), 1);

  // A finished submap held elsewhere is not touched by later insertions.
  EXPECT_EQ(all[0]->num_range_data(), 2 * kN);
  EXPECT_EQ(all[1]->num_range_data(), 2 * kN);
}

TEST(SubmapsOptionsTest, ParseReadsNestedInserterOptions) {
  std::string error;
  auto reader = common::ConfigReader::FromString(
      "num_range_data: 60\nresolution_m: 0.1\nrange_data_inserter:\n  hit_probability: 0.6\n",
      "s.yaml", &error);
  ASSERT_NE(reader, nullptr) << error;
  const SubmapsOptions options = ParseSubmapsOptions(*reader);
  EXPECT_TRUE(reader->Finish(&error)) << error;
  EXPECT_EQ(options.num_range_data, 60);
  EXPECT_DOUBLE_EQ(options.resolution_m, 0.1);
  EXPECT_FLOAT_EQ(options.range_data_inserter.hit_probability, 0.6f);
  EXPECT_TRUE(options.IsValid(&error)) << error;
  auto bad = common::ConfigReader::FromString("num_range_data: 0\n", "b.yaml", &error);
  ParseSubmapsOptions(*bad);
  EXPECT_FALSE(bad->Finish(&error));
}

}  // namespace
}  // namespace mapping
}  // namespace fusemap
