#include "fusemap/pose_graph/sparse_pose_adjustment_2d.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "fusemap/common/math.h"

namespace fusemap {
namespace pose_graph {
namespace {

using common::Rigid2d;

constexpr int kNodesPerSide = 10;
constexpr int kNumNodes = 4 * kNodesPerSide;  // 1 m apart around a 10 m square
constexpr int kNodesPerSubmap = 10;

// Ground truth, noisy drifting odometry, and an SPA problem built from them the way local SLAM
// would: initial poses integrate odometry, intra-submap constraints are accurate to ~1 cm.
struct SquareLoop {
  std::vector<Rigid2d> truth;
  SparsePoseAdjustment2D spa;
};

// Motion from node k to k + 1: 1 m ahead, turning left at the corners.
Rigid2d Step(int k) {
  return Rigid2d(1.0, 0.0, k % kNodesPerSide == kNodesPerSide - 1 ? common::kPi / 2 : 0.0);
}

Rigid2d Noise(std::mt19937* rng, double sigma_m, double sigma_rad) {
  std::normal_distribution<double> n(0.0, 1.0);
  const double x = sigma_m * n(*rng), y = sigma_m * n(*rng), a = sigma_rad * n(*rng);
  return Rigid2d(x, y, a);
}

void BuildSquareLoop(SquareLoop* loop) {
  std::mt19937 rng(42);
  loop->truth.push_back(Rigid2d::Identity());
  for (int k = 0; k + 1 < kNumNodes; ++k) loop->truth.push_back(loop->truth[k] * Step(k));
  // Odometry: 2 cm / 0.3 deg noise per step plus a 0.01 rad per step heading bias (drift).
  std::vector<Rigid2d> odometry;
  for (int k = 0; k + 1 < kNumNodes; ++k) {
    odometry.push_back(Step(k) * Rigid2d(0.0, 0.0, 0.01) * Noise(&rng, 0.02, 0.005));
  }
  Rigid2d estimate = Rigid2d::Identity();
  loop->spa.AddNode(estimate);
  for (const Rigid2d& step : odometry) loop->spa.AddNode(estimate = estimate * step);
  for (int s = 0; s * kNodesPerSubmap < kNumNodes; ++s) {
    loop->spa.AddSubmap(loop->spa.T_map_nodes()[s * kNodesPerSubmap]);
  }
  for (int k = 0; k + 1 < kNumNodes; ++k) {
    loop->spa.AddNodeToNodeConstraint({k, k + 1, odometry[k], 1.0, 1.0});
  }
  // Each submap holds its nodes and the first node of the next submap.
  for (int s = 0; s * kNodesPerSubmap < kNumNodes; ++s) {
    const int anchor = s * kNodesPerSubmap;
    for (int k = anchor; k <= std::min(anchor + kNodesPerSubmap, kNumNodes - 1); ++k) {
      const Rigid2d measured =
          loop->truth[anchor].inverse() * loop->truth[k] * Noise(&rng, 0.01, 0.002);
      loop->spa.AddConstraint({s, k, measured, 10.0, 50.0, Constraint2D::kIntraSubmap});
    }
  }
  // Loop closure: the last two nodes seen again in submap 0.
  for (int k = kNumNodes - 2; k < kNumNodes; ++k) {
    loop->spa.AddConstraint({0, k, loop->truth[k] * Noise(&rng, 0.01, 0.002), 10.0, 50.0,
                             Constraint2D::kInterSubmap});
  }
}

double MaxNodeError(const SquareLoop& loop) {
  double max_error_m = 0.0;
  for (int k = 0; k < kNumNodes; ++k) {
    const Rigid2d& node = loop.spa.T_map_nodes()[k];
    max_error_m = std::max(max_error_m, (node.translation() - loop.truth[k].translation()).norm());
  }
  return max_error_m;
}

TEST(SparsePoseAdjustment2DTest, RecoversSquareLoopFromDriftedOdometry) {
  SquareLoop loop;
  BuildSquareLoop(&loop);
  const double initial_error_m = MaxNodeError(loop);
  EXPECT_GT(initial_error_m, 1.5);  // 2.1 m with this seed
  const OptimizationSummary summary = loop.spa.Solve(OptimizationOptions());
  EXPECT_TRUE(summary.converged);
  EXPECT_LT(summary.final_cost, 1e-2 * summary.initial_cost);
  // 4.7 cm with this seed: 1 cm / 0.1 deg constraint noise chained over 10 m lever arms.
  EXPECT_LT(MaxNodeError(loop), 0.1);
  for (int s = 0; s < 4; ++s) {
    const Rigid2d& truth = loop.truth[s * kNodesPerSubmap];
    const Rigid2d& pose = loop.spa.T_map_submaps()[s];
    EXPECT_NEAR((pose.translation() - truth.translation()).norm(), 0.0, 0.05) << s;
    EXPECT_NEAR(common::NormalizeAngle(pose.angle_rad() - truth.angle_rad()), 0.0, 0.01) << s;
  }
}

TEST(SparsePoseAdjustment2DTest, HoldsFirstSubmapConstant) {
  SquareLoop loop;
  BuildSquareLoop(&loop);
  const Rigid2d offset(0.7, -0.4, 0.2);
  loop.spa.SetSubmapPose(0, offset);
  const std::vector<Rigid2d> before = loop.spa.T_map_submaps();
  loop.spa.Solve(OptimizationOptions());
  EXPECT_EQ(loop.spa.T_map_submaps()[0].x(), offset.x());
  EXPECT_EQ(loop.spa.T_map_submaps()[0].y(), offset.y());
  EXPECT_EQ(loop.spa.T_map_submaps()[0].angle_rad(), offset.angle_rad());
  // The rest of the map follows the moved anchor: node 0 lands at offset * truth[0].
  EXPECT_NEAR((loop.spa.T_map_nodes()[0].translation() - offset.translation()).norm(), 0.0, 0.05);
  EXPECT_GT((loop.spa.T_map_submaps()[2].translation() - before[2].translation()).norm(), 0.5);
}

TEST(SparsePoseAdjustment2DTest, HuberLossDownweightsWrongLoopClosure) {
  double error_m[2];
  for (const bool use_huber : {false, true}) {
    SquareLoop loop;
    BuildSquareLoop(&loop);
    // Node 25 claimed 3 m and 0.5 rad away from where it is in submap 0.
    loop.spa.AddConstraint({0, 25, loop.truth[25] * Rigid2d(3.0, -2.0, 0.5), 10.0, 50.0,
                            Constraint2D::kInterSubmap});
    OptimizationOptions options;
    options.huber_scale = use_huber ? 0.1 : 0.0;
    loop.spa.Solve(options);
    error_m[use_huber] = MaxNodeError(loop);
  }
  // 2.9 m without the loss, 8.7 cm with it (4.7 cm without the wrong closure).
  EXPECT_GT(error_m[0], 1.0);
  EXPECT_LT(error_m[1], 0.15);
}

// A corridor loop closure slid 3 m along the corridor (the node's x axis) pulls the graph by 3 m,
// unless it says it measures nothing along that axis; what it measures across is still used.
TEST(SparsePoseAdjustment2DTest, NothingAlongAnUnmeasuredDirection) {
  double error_m[2];
  for (const bool unmeasured : {false, true}) {
    SquareLoop loop;
    BuildSquareLoop(&loop);
    Constraint2D slid{0, 25, loop.truth[25] * Rigid2d(3.0, 0.0, 0.0), 10.0, 50.0,
                      Constraint2D::kInterSubmap};
    if (unmeasured) slid.unmeasured_direction = Eigen::Vector2d::UnitX();
    loop.spa.AddConstraint(slid);
    OptimizationOptions options;
    options.huber_scale = 0.0;
    loop.spa.Solve(options);
    error_m[unmeasured] = MaxNodeError(loop);
  }
  // 4.7 cm without the slid closure.
  EXPECT_GT(error_m[0], 1.0);
  EXPECT_LT(error_m[1], 0.1);
}

TEST(SparsePoseAdjustment2DTest, SnapshotIsAnImmutableCopy) {
  SquareLoop loop;
  BuildSquareLoop(&loop);
  const std::shared_ptr<const PoseGraphSnapshot> before = loop.spa.Snapshot();
  loop.spa.Solve(OptimizationOptions());
  const std::shared_ptr<const PoseGraphSnapshot> after = loop.spa.Snapshot();
  EXPECT_EQ(before->solve_count, 0u);
  EXPECT_EQ(after->solve_count, 1u);
  ASSERT_EQ(before->T_map_nodes.size(), static_cast<size_t>(kNumNodes));
  EXPECT_GT((before->T_map_nodes[30].translation() - after->T_map_nodes[30].translation()).norm(),
            0.5);
  EXPECT_EQ(after->T_map_submaps.size(), 4u);
}

TEST(OptimizationOptionsTest, RejectsBadValues) {
  std::string error;
  EXPECT_TRUE(OptimizationOptions().IsValid(&error));
  OptimizationOptions options;
  options.huber_scale = -1.0;
  EXPECT_FALSE(options.IsValid(&error));
  options = OptimizationOptions();
  options.linear_solver = "magic";
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("linear_solver"), std::string::npos);
}

TEST(OptimizationOptionsTest, ParsesFromConfig) {
  std::string error;
  auto reader = common::ConfigReader::FromString(
      "huber_scale: 0.5\nmax_num_iterations: 7\nlinear_solver: dense_qr\n", "test.yaml", &error);
  ASSERT_NE(reader, nullptr) << error;
  const OptimizationOptions options = ParseOptimizationOptions(*reader);
  EXPECT_TRUE(reader->Finish(&error)) << error;
  EXPECT_EQ(options.huber_scale, 0.5);
  EXPECT_EQ(options.max_num_iterations, 7);
  EXPECT_EQ(options.linear_solver, "dense_qr");

  auto bad = common::ConfigReader::FromString("num_threads: 0\n", "bad.yaml", &error);
  ASSERT_NE(bad, nullptr) << error;
  ParseOptimizationOptions(*bad);
  EXPECT_FALSE(bad->Finish(&error));
  EXPECT_NE(error.find("num_threads"), std::string::npos) << error;
}

}  // namespace
}  // namespace pose_graph
}  // namespace fusemap
