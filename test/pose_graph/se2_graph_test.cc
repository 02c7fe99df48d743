#include "fusemap/pose_graph/se2_graph.h"

#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <memory>

#include "fusemap/common/math.h"
#include "fusemap/pose_graph/se2_cost_function.h"

namespace fusemap {
namespace pose_graph {
namespace {

using common::Rigid2d;

TEST(Se2CostFunctionTest, ResidualIsWhitenedErrorInMeasurementFrame) {
  const Rigid2d T_map_from(1.0, 2.0, 0.5);
  const Rigid2d T_from_to(2.0, -1.0, common::kPi - 0.01);
  const Rigid2d T_map_to = T_map_from * T_from_to * Rigid2d(0.1, -0.2, 0.03);
  const Eigen::Vector3d error = Se2EdgeError(T_map_from, T_map_to, T_from_to);
  EXPECT_NEAR(error.x(), 0.1, 1e-12);
  EXPECT_NEAR(error.y(), -0.2, 1e-12);
  EXPECT_NEAR(error.z(), 0.03, 1e-12);  // across the +-pi seam

  Eigen::Matrix3d sqrt_information;
  ASSERT_TRUE(SqrtInformation(InformationFromWeights(3.0, 7.0), &sqrt_information));
  std::unique_ptr<ceres::CostFunction> cost(CreateSe2EdgeCostFunction(T_from_to, sqrt_information));
  const double from[3] = {T_map_from.x(), T_map_from.y(), T_map_from.angle_rad()};
  const double to[3] = {T_map_to.x(), T_map_to.y(), T_map_to.angle_rad()};
  const double* parameters[2] = {from, to};
  double residual[3];
  ASSERT_TRUE(cost->Evaluate(parameters, residual, nullptr));
  EXPECT_NEAR(residual[0], 0.3, 1e-12);
  EXPECT_NEAR(residual[1], -0.6, 1e-12);
  EXPECT_NEAR(residual[2], 0.21, 1e-12);
}

TEST(Se2CostFunctionTest, SqrtInformationRejectsNonPositiveDefinite) {
  Eigen::Matrix3d information;
  information << 4, 1, 0, 1, 3, 0.5, 0, 0.5, 2;
  Eigen::Matrix3d s;
  ASSERT_TRUE(SqrtInformation(information, &s));
  EXPECT_TRUE((s.transpose() * s).isApprox(information, 1e-12));
  EXPECT_EQ(s(1, 0), 0.0);
  information(1, 1) = 0.1;  // det < 0
  EXPECT_FALSE(SqrtInformation(information, &s));
  EXPECT_FALSE(SqrtInformation(Eigen::Vector3d(1, 0, 1).asDiagonal().toDenseMatrix(), &s));
}

// A triangle whose third edge disagrees by 0.3 m with the chain of the other two.
Se2Graph Triangle() {
  Se2Graph graph;
  graph.vertices.assign(3, Rigid2d::Identity());
  graph.edges.push_back({0, 1, Rigid2d(1, 0, common::kPi / 2), Eigen::Matrix3d::Identity(), false});
  graph.edges.push_back({1, 2, Rigid2d(1, 0, common::kPi / 2), Eigen::Matrix3d::Identity(), false});
  graph.edges.push_back({0, 2, Rigid2d(1, 1.3, common::kPi), Eigen::Matrix3d::Identity(), false});
  return graph;
}

TEST(Se2GraphTest, InitializesAlongOdometryChain) {
  Se2Graph graph = Triangle();
  EXPECT_EQ(InitializeFromEdges(&graph), 3);
  // Vertex 2 is reached by the odometry edges 0-1-2, not by the direct closure 0-2.
  EXPECT_NEAR(graph.vertices[2].x(), 1.0, 1e-12);
  EXPECT_NEAR(graph.vertices[2].y(), 1.0, 1e-12);
  EXPECT_NEAR(std::abs(graph.vertices[2].angle_rad()), common::kPi, 1e-12);
  EXPECT_NEAR(Se2GraphCost(graph), 0.5 * 0.3 * 0.3, 1e-12);
}

TEST(Se2GraphTest, SolveSpreadsErrorAndKeepsGaugeFixed) {
  Se2Graph graph = Triangle();
  InitializeFromEdges(&graph);
  OptimizationOptions options;
  options.huber_scale = 0.0;
  const OptimizationSummary summary = SolveSe2Graph(options, &graph);
  EXPECT_TRUE(summary.converged);
  EXPECT_NEAR(summary.initial_cost, 0.045, 1e-9);
  EXPECT_LT(summary.final_cost, 0.5 * summary.initial_cost);
  EXPECT_NEAR(summary.final_cost, Se2GraphCost(graph), 1e-12);
  EXPECT_EQ(graph.vertices[0].x(), 0.0);
  EXPECT_EQ(graph.vertices[0].angle_rad(), 0.0);

  Se2Graph fixed_last = Triangle();
  InitializeFromEdges(&fixed_last);
  fixed_last.fixed = {false, false, true};
  const Rigid2d held = fixed_last.vertices[2];
  SolveSe2Graph(options, &fixed_last);
  EXPECT_EQ(fixed_last.vertices[2].x(), held.x());
  EXPECT_NE(fixed_last.vertices[0].x(), 0.0);
}

}  // namespace
}  // namespace pose_graph
}  // namespace fusemap
