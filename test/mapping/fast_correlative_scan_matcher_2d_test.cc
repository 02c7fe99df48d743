#include "fusemap/mapping/scan_matching/fast_correlative_scan_matcher_2d.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "testing/wall_grid.h"

namespace fusemap {
namespace mapping {
namespace {

struct BruteForceResult {
  long best_sum = -1;
  std::vector<common::Rigid2d> best_poses;  // every candidate reaching best_sum
};

// Visits every candidate the matcher's search would contain (same angles, same integer cell
// offsets, same quantised values), with no pyramid: visit(candidate, pose, sum of the
// precomputation values of its cells, number of cells).
template <typename Visit>
void ForEachCandidate(const ProbabilityGrid& grid, const common::Rigid2d& initial_pose,
                      const sensor::PointCloud2d& cloud, double linear_window_m,
                      double angular_window_rad, Visit visit) {
  SearchParameters params(linear_window_m, angular_window_rad, cloud, grid.limits().resolution_m);
  const Eigen::Matrix2f rotation =
      Eigen::Rotation2Df(static_cast<float>(initial_pose.angle_rad())).matrix();
  sensor::PointCloud2d rotated;
  for (const Eigen::Vector2f& p : cloud) rotated.push_back(rotation * p);
  const std::vector<DiscreteScan2D> scans = DiscretizeScans(
      grid.limits(), GenerateRotatedScans(rotated, params), initial_pose.translation().cast<float>());
  params.ShrinkToFit(scans, grid.limits());
  for (int i = 0; i < params.num_scans; ++i) {
    const SearchParameters::LinearBounds& b = params.linear_bounds[i];
    for (int x = b.min_x; x <= b.max_x; ++x) {
      for (int y = b.min_y; y <= b.max_y; ++y) {
        long sum = 0;
        for (const Eigen::Array2i& cell : scans[i]) {
          sum += ProbabilityToPrecomputationValue(grid.GetProbability(cell + Eigen::Array2i(x, y)));
        }
        const Candidate2D c(i, x, y, params);
        visit(c,
              common::Rigid2d(initial_pose.translation() + Eigen::Vector2d(c.x_m, c.y_m),
                              initial_pose.angle_rad() + c.angle_rad),
              sum, static_cast<int>(scans[i].size()));
      }
    }
  }
}

// The best sum over every candidate, and every candidate reaching it.
BruteForceResult BruteForce(const ProbabilityGrid& grid, const common::Rigid2d& initial_pose,
                            const sensor::PointCloud2d& cloud, double linear_window_m,
                            double angular_window_rad) {
  BruteForceResult result;
  ForEachCandidate(grid, initial_pose, cloud, linear_window_m, angular_window_rad,
                   [&result](const Candidate2D&, const common::Rigid2d& pose, long sum, int) {
                     if (sum < result.best_sum) return;
                     if (sum > result.best_sum) result.best_poses.clear();
                     result.best_sum = sum;
                     result.best_poses.push_back(pose);
                   });
  return result;
}

// White noise (bounds loose, little pruning) when `smooth` is false; otherwise a sum of random
// bumps, where upper bounds are tight and near-ties between subtrees make pruning decide.
ProbabilityGrid MakeRandomGrid(int num_x, int num_y, bool smooth, std::mt19937* rng) {
  MapLimits limits;
  limits.resolution_m = 0.05;
  limits.origin_m = Eigen::Vector2d(-1.0, -0.5);
  limits.num_x_cells = num_x;
  limits.num_y_cells = num_y;
  ProbabilityGrid grid(limits);
  std::uniform_real_distribution<float> unit(0.f, 1.f);
  std::vector<Eigen::Vector3f> bumps;  // x, y, sigma in cells
  for (int i = 0; i < 30; ++i) bumps.emplace_back(num_x * unit(*rng), num_y * unit(*rng), 1.f + 4.f * unit(*rng));
  for (int y = 0; y < num_y; ++y) {
    for (int x = 0; x < num_x; ++x) {
      float p = unit(*rng);
      if (smooth) {
        p = 0.f;
        for (const Eigen::Vector3f& b : bumps) {
          const float d2 = (Eigen::Vector2f(x, y) - b.head<2>()).squaredNorm();
          p = std::max(p, std::exp(-d2 / (2.f * b.z() * b.z())));
        }
      }
      if (p > 0.15f) grid.SetProbability(Eigen::Array2i(x, y), p);
    }
  }
  return grid;
}

// A random grid (smooth for two seeds in three), 40 random points and a random start, with a
// search window the brute force can cover.
struct RandomMatchProblem {
  explicit RandomMatchProblem(unsigned seed)
      : rng(seed), grid(MakeRandomGrid(60, 50, /*smooth=*/seed % 3 != 0, &rng)) {
    std::uniform_real_distribution<double> coordinate(-0.2, 1.8);
    std::uniform_real_distribution<double> angle(-common::kPi, common::kPi);
    std::uniform_real_distribution<float> offset(-1.2f, 1.2f);
    for (int i = 0; i < 40; ++i) cloud.emplace_back(offset(rng), offset(rng));
    initial = common::Rigid2d(coordinate(rng), coordinate(rng) - 0.5, angle(rng));
    options.linear_search_window_m = 0.6;
    options.angular_search_window_rad = common::DegToRad(8.0);
  }
  std::mt19937 rng;
  ProbabilityGrid grid;
  sensor::PointCloud2d cloud;
  common::Rigid2d initial;
  FastCorrelativeScanMatcherOptions2D options;
};

TEST(FastCorrelativeScanMatcher2DTest, BranchAndBoundEqualsBruteForce) {
  for (unsigned seed = 1; seed <= 12; ++seed) {
    SCOPED_TRACE(seed);
    const RandomMatchProblem problem(seed);
    const ProbabilityGrid& grid = problem.grid;
    const sensor::PointCloud2d& cloud = problem.cloud;
    const common::Rigid2d& initial = problem.initial;
    FastCorrelativeScanMatcherOptions2D options = problem.options;
    // Depth 2 splits the window finely; depth 6 has top-level windows wider than the search.
    for (int depth : {2, 4, 6}) {
      SCOPED_TRACE(depth);
      options.branch_and_bound_depth = depth;
      const FastCorrelativeScanMatcher2D matcher(grid, options);
      const BruteForceResult expected = BruteForce(grid, initial, cloud, options.linear_search_window_m,
                                                   options.angular_search_window_rad);
      ASSERT_FALSE(expected.best_poses.empty());
      const double expected_score = PrecomputationScore(expected.best_sum, 40);
      double score = 0.0;
      common::Rigid2d pose;
      ASSERT_TRUE(matcher.Match(initial, cloud, 0.0, &score, &pose));
      EXPECT_NEAR(score, expected_score, 1e-6);
      const bool is_a_best_pose = std::any_of(
          expected.best_poses.begin(), expected.best_poses.end(), [&](const common::Rigid2d& p) {
            return (p.translation() - pose.translation()).norm() < 1e-9 &&
                   std::abs(common::NormalizeAngle(p.angle_rad() - pose.angle_rad())) < 1e-9;
          });
      EXPECT_TRUE(is_a_best_pose) << pose.DebugString();
      // Just above / below the best score the matcher must fail / succeed.
      EXPECT_FALSE(matcher.Match(initial, cloud, expected_score, &score, &pose));
      EXPECT_TRUE(matcher.Match(initial, cloud, expected_score - 1e-6, &score, &pose));
    }
  }
}

// The best prior-weighted score over the same candidates as BruteForce, and its pose.
struct PriorBruteForceResult {
  double best_score = -1.0;  // with the prior
  double match_score = 0.0;  // of the same candidate, without
  common::Rigid2d best_pose;
};

PriorBruteForceResult BruteForceWithPrior(const ProbabilityGrid& grid,
                                          const common::Rigid2d& initial_pose,
                                          const sensor::PointCloud2d& cloud,
                                          const FastCorrelativeScanMatcherOptions2D& options) {
  PriorBruteForceResult result;
  ForEachCandidate(
      grid, initial_pose, cloud, options.linear_search_window_m, options.angular_search_window_rad,
      [&](const Candidate2D& c, const common::Rigid2d& pose, long sum, int num_cells) {
        const double cost = std::hypot(c.x_m, c.y_m) * options.translation_delta_cost_weight +
                            std::abs(c.angle_rad) * options.rotation_delta_cost_weight;
        const double match_score = PrecomputationScore(sum, num_cells);
        const double score = match_score * std::exp(-cost * cost);
        if (score <= result.best_score) return;
        result.best_score = score;
        result.match_score = match_score;
        result.best_pose = pose;
      });
  return result;
}

// With a prior on the search centre, branch and bound still finds the exhaustive search's
// best prior-weighted candidate: each subtree's bound uses its offset nearest the centre.
TEST(FastCorrelativeScanMatcher2DTest, BranchAndBoundWithPriorEqualsBruteForce) {
  for (unsigned seed = 1; seed <= 12; ++seed) {
    SCOPED_TRACE(seed);
    const RandomMatchProblem problem(seed);
    const ProbabilityGrid& grid = problem.grid;
    const sensor::PointCloud2d& cloud = problem.cloud;
    const common::Rigid2d& initial = problem.initial;
    FastCorrelativeScanMatcherOptions2D options = problem.options;
    options.translation_delta_cost_weight = 0.5 + 0.2 * (seed % 4);
    options.rotation_delta_cost_weight = 3.0 * (seed % 3);
    for (int depth : {2, 4, 6}) {
      SCOPED_TRACE(depth);
      options.branch_and_bound_depth = depth;
      const FastCorrelativeScanMatcher2D matcher(grid, options);
      const PriorBruteForceResult expected = BruteForceWithPrior(grid, initial, cloud, options);
      ASSERT_GT(expected.best_score, 0.0);
      double score = 0.0;
      common::Rigid2d pose;
      ASSERT_TRUE(matcher.Match(initial, cloud, 0.0, &score, &pose));
      // Ties between candidates are improbable with a continuous prior.
      EXPECT_NEAR((pose.translation() - expected.best_pose.translation()).norm(), 0.0, 1e-9);
      EXPECT_NEAR(common::NormalizeAngle(pose.angle_rad() - expected.best_pose.angle_rad()), 0.0,
                  1e-9);
      // The score and the threshold are the match's own, without the prior.
      EXPECT_NEAR(score, expected.match_score, 1e-9);
      EXPECT_FALSE(matcher.Match(initial, cloud, expected.match_score + 1e-9, &score, &pose));
      EXPECT_TRUE(matcher.Match(initial, cloud, expected.match_score - 1e-9, &score, &pose));
      // At any threshold the answer is that candidate or none, never another that beats the
      // threshold but ranks lower (the search prunes by the threshold too).
      for (double min_score = 0.05; min_score < 1.0; min_score += 0.05) {
        SCOPED_TRACE(min_score);
        const bool found = matcher.Match(initial, cloud, min_score, &score, &pose);
        ASSERT_EQ(found, expected.match_score > min_score);
        if (!found) continue;
        EXPECT_NEAR((pose.translation() - expected.best_pose.translation()).norm(), 0.0, 1e-9);
        EXPECT_NEAR(score, expected.match_score, 1e-9);
      }
    }
  }
}

// CellsReadByMatch holds every cell the search can read: each rotated scan's cells (as the
// search rotates and rounds them) moved by every offset of the window. And a matcher over a
// stack built for those cells only gives the answer of one over the whole grid, with and
// without a prior, at several thresholds.
TEST(FastCorrelativeScanMatcher2DTest, StackForTheCellsReadGivesTheSameAnswer) {
  for (unsigned seed = 1; seed <= 12; ++seed) {
    SCOPED_TRACE(seed);
    RandomMatchProblem problem(seed);
    FastCorrelativeScanMatcherOptions2D options = problem.options;
    // Wider than the problem's, as local SLAM's wide search: far points sweep long arcs.
    options.angular_search_window_rad = 0.5;
    options.branch_and_bound_depth = 2 + seed % 5;  // blocked levels from 4 on
    if (seed % 2 == 0) options.translation_delta_cost_weight = 0.5;
    const MapLimits& limits = problem.grid.limits();
    const CellBox reads = CellsReadByMatch(limits, options, problem.initial, problem.cloud);

    const SearchParameters params(options.linear_search_window_m, options.angular_search_window_rad,
                                  problem.cloud, limits.resolution_m);
    const Eigen::Matrix2f rotation =
        Eigen::Rotation2Df(static_cast<float>(problem.initial.angle_rad())).matrix();
    sensor::PointCloud2d rotated;
    for (const Eigen::Vector2f& point : problem.cloud) rotated.push_back(rotation * point);
    const int num_linear = params.linear_bounds.front().max_x;
    for (const DiscreteScan2D& scan :
         DiscretizeScans(limits, GenerateRotatedScans(rotated, params),
                         problem.initial.translation().cast<float>())) {
      for (const Eigen::Array2i& cell : scan) {
        ASSERT_TRUE((cell - num_linear >= reads.min_cell).all());
        ASSERT_LT(cell.x() + num_linear, reads.min_cell.x() + reads.num_x_cells);
        ASSERT_LT(cell.y() + num_linear, reads.min_cell.y() + reads.num_y_cells);
      }
    }

    const CellBox whole_grid{Eigen::Array2i::Zero(), limits.num_x_cells, limits.num_y_cells};
    const FastCorrelativeScanMatcher2D whole(problem.grid, options);
    const FastCorrelativeScanMatcher2D part(
        limits,
        PrecomputationGridStack2D(problem.grid, whole_grid, kMinProbability,
                                  options.branch_and_bound_depth, reads),
        options);
    for (double min_score : {0.0, 0.3, 0.5, 0.6}) {
      double whole_score = 0.0;
      double part_score = 0.0;
      common::Rigid2d whole_pose;
      common::Rigid2d part_pose;
      const bool found =
          whole.Match(problem.initial, problem.cloud, min_score, &whole_score, &whole_pose);
      ASSERT_EQ(part.Match(problem.initial, problem.cloud, min_score, &part_score, &part_pose),
                found)
          << min_score;
      if (!found) continue;
      EXPECT_EQ(part_score, whole_score);
      EXPECT_EQ(part_pose.translation(), whole_pose.translation());
      EXPECT_EQ(part_pose.angle_rad(), whole_pose.angle_rad());
    }
  }
}

// Two posts of 2 x 4 cells, at x = -0.3 and x = 0.7 (their cells' probabilities given), a
// scan of one post, and a search 1 m along x (no rotation) around x = 0.25, from where the post
// at 0.7 is 0.45 m away and the one at -0.3 0.55 m.
struct TwoPosts {
  TwoPosts(float left_probability, float right_probability) : grid(Limits()) {
    for (int i = 0; i < 8; ++i) {
      // Cell centres, so that no point sits on a cell boundary.
      const Eigen::Vector2f in_post(0.025f + 0.05f * (i % 2), 0.025f + 0.05f * (i / 2));
      const MapLimits& limits = grid.limits();
      grid.SetProbability(limits.GetCellIndex(in_post + Eigen::Vector2f(-0.3f, 0.f)),
                          left_probability);
      grid.SetProbability(limits.GetCellIndex(in_post + Eigen::Vector2f(0.7f, 0.f)),
                          right_probability);
      cloud.push_back(in_post);
    }
    options.linear_search_window_m = 1.0;
    options.angular_search_window_rad = 0.0;
    options.branch_and_bound_depth = 4;
  }
  // 4 m x 4 m of 5 cm cells around the origin.
  static MapLimits Limits() { return MapLimits{0.05, Eigen::Vector2d(-2.0, -2.0), 80, 80}; }
  ProbabilityGrid grid;
  sensor::PointCloud2d cloud;
  FastCorrelativeScanMatcherOptions2D options;
  const common::Rigid2d centre{0.25, 0.0, 0.0};
};

// The prior pulls the answer to the nearer of two equally good places.
TEST(FastCorrelativeScanMatcher2DTest, PriorPrefersTheNearerOfTwoEqualMatches) {
  TwoPosts posts(0.9f, 0.9f);
  posts.options.translation_delta_cost_weight = 1.0;
  double score = 0.0;
  common::Rigid2d pose;
  ASSERT_TRUE(FastCorrelativeScanMatcher2D(posts.grid, posts.options)
                  .Match(posts.centre, posts.cloud, 0.0, &score, &pose));
  EXPECT_NEAR(pose.translation().x(), 0.7, 1e-6);
  EXPECT_NEAR(score, 0.9, 2e-3);
}

// Of two posts, the nearer fits less well than the further but the prior ranks it first. A
// threshold between their fits finds no answer: the first-ranked candidate does not beat it,
// and the further post is not the answer just because it does.
TEST(FastCorrelativeScanMatcher2DTest, ThresholdBetweenTwoFitsFindsNoAnswer) {
  TwoPosts posts(0.88f, 0.7f);
  // The post at 0.7 ranks 0.7 * exp(-(2 * 0.45)^2) = 0.31, the one at -0.3
  // 0.88 * exp(-(2 * 0.55)^2) = 0.26.
  posts.options.translation_delta_cost_weight = 2.0;
  const FastCorrelativeScanMatcher2D matcher(posts.grid, posts.options);
  double score = 0.0;
  common::Rigid2d pose;
  ASSERT_TRUE(matcher.Match(posts.centre, posts.cloud, 0.6, &score, &pose));
  EXPECT_NEAR(pose.translation().x(), 0.7, 1e-6);
  EXPECT_NEAR(score, 0.7, 2e-3);
  EXPECT_FALSE(matcher.Match(posts.centre, posts.cloud, 0.8, &score, &pose)) << pose.DebugString();
}

// A decoy copy B of the scan (cells at 0.79) whose coarse windows also hold one 0.9 cell per
// point, each at a different place, so B's upper bounds beat the true copy A and B's subtree is
// searched first. A equals B except for one cell one quantisation step higher, so A's bound
// exceeds B's best leaf by the smallest possible score difference: pruning with any slack
// would lose the optimum.
TEST(FastCorrelativeScanMatcher2DTest, SlightlyBetterLeafInLaterSubtreeIsFound) {
  MapLimits limits;
  limits.resolution_m = 0.05;
  limits.num_x_cells = 160;
  limits.num_y_cells = 120;
  ProbabilityGrid grid(limits);
  sensor::PointCloud2d cloud;
  std::vector<Eigen::Array2i> cells;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      cells.emplace_back(50 + 10 * i, 40 + 10 * j);
      cloud.push_back(limits.GetCellCenter(cells.back()).cast<float>());
    }
  }
  const Eigen::Array2i offset_a(16, 8);
  const Eigen::Array2i offset_b(-16, 0);  // both multiples of the depth-3 width 8
  for (size_t k = 0; k < cells.size(); ++k) {
    grid.SetProbability(cells[k] + offset_a, k == 0 ? 0.7934f : 0.79f);
    grid.SetProbability(cells[k] + offset_b, 0.79f);
    const Eigen::Array2i distinct_in_window(k % 8, 4 * (k / 8) + 1 + k % 3);
    grid.SetProbability(cells[k] + offset_b + distinct_in_window, 0.9f);
  }
  FastCorrelativeScanMatcherOptions2D options;
  options.linear_search_window_m = 2.0;
  options.angular_search_window_rad = 0.0;
  options.branch_and_bound_depth = 3;
  const FastCorrelativeScanMatcher2D matcher(grid, options);
  double score = 0.0;
  common::Rigid2d pose;
  ASSERT_TRUE(matcher.Match(common::Rigid2d::Identity(), cloud, 0.5, &score, &pose));
  ASSERT_EQ(ProbabilityToPrecomputationValue(0.79f) + 1, ProbabilityToPrecomputationValue(0.7934f));
  EXPECT_NEAR(score, PrecomputationScore(16 * ProbabilityToPrecomputationValue(0.79f) + 1, 16), 1e-12);
  EXPECT_NEAR(pose.x(), 0.8, 1e-9);
  EXPECT_NEAR(pose.y(), 0.4, 1e-9);
  EXPECT_EQ(pose.angle_rad(), 0.0);
  const BruteForceResult expected = BruteForce(grid, common::Rigid2d::Identity(), cloud, 2.0, 0.0);
  EXPECT_NEAR(score, PrecomputationScore(expected.best_sum, 16), 1e-12);
}

using test_world::Segment;

// Outer walls of a 20 m x 20 m hall plus random walls and pillars: unique enough to localise.
std::vector<Segment> MakeStructuredWorld(unsigned seed) {
  std::vector<Segment> segments = {{{0.5, 0.5}, {19.5, 0.5}}, {{19.5, 0.5}, {19.5, 19.5}},
                                   {{19.5, 19.5}, {0.5, 19.5}}, {{0.5, 19.5}, {0.5, 0.5}}};
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> position(1.5, 18.5);
  std::uniform_real_distribution<double> length(0.5, 3.0);
  std::uniform_real_distribution<double> direction(0.0, common::kPi);
  for (int i = 0; i < 25; ++i) {
    const Eigen::Vector2d a(position(rng), position(rng));
    const double l = length(rng);
    const double t = direction(rng);
    segments.push_back({a, a + l * Eigen::Vector2d(std::cos(t), std::sin(t))});
  }
  return segments;
}

ProbabilityGrid DrawWorld(const std::vector<Segment>& segments) {
  MapLimits limits;
  limits.resolution_m = 0.05;
  limits.num_x_cells = 400;
  limits.num_y_cells = 400;
  return test_world::DrawWalls(limits, segments, /*cutoff_m=*/0.3);
}

sensor::PointCloud2d CastScan(const std::vector<Segment>& segments, const common::Rigid2d& T_grid_tracking,
                              int num_beams, double range_max_m) {
  return test_world::CastCloud(segments, T_grid_tracking, num_beams, range_max_m);
}

TEST(FastCorrelativeScanMatcher2DTest, FindsScanDisplacedByTwoMetresAndTwentyDegrees) {
  const std::vector<Segment> world = MakeStructuredWorld(7);
  const ProbabilityGrid grid = DrawWorld(world);
  const FastCorrelativeScanMatcherOptions2D options;  // 7 m, 30 deg, depth 7
  const FastCorrelativeScanMatcher2D matcher(grid, options);
  for (const common::Rigid2d& truth : {common::Rigid2d(6.0, 7.0, 0.4), common::Rigid2d(13.2, 11.1, -2.5)}) {
    SCOPED_TRACE(truth.DebugString());
    const sensor::PointCloud2d cloud = CastScan(world, truth, 180, 12.0);
    ASSERT_GT(cloud.size(), 150u);
    const common::Rigid2d initial(truth.x() + 1.2, truth.y() - 1.6, truth.angle_rad() + common::DegToRad(20.0));
    double score = 0.0;
    common::Rigid2d pose;
    const auto start = std::chrono::steady_clock::now();
    ASSERT_TRUE(matcher.Match(initial, cloud, options.min_score, &score, &pose));
    const double elapsed_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::printf("local branch-and-bound match: %.1f ms, score %.3f\n", elapsed_ms, score);
    // One cell plus the lattice offset of the start; half an angular step (< 0.3 deg here).
    EXPECT_LT((pose.translation() - truth.translation()).norm(), 0.05);
    EXPECT_LT(std::abs(common::NormalizeAngle(pose.angle_rad() - truth.angle_rad())), common::DegToRad(0.5));
    EXPECT_GT(score, 0.7);
  }
}

TEST(FastCorrelativeScanMatcher2DTest, FullSubmapSearchFindsUnknownPose) {
  const std::vector<Segment> world = MakeStructuredWorld(11);
  const ProbabilityGrid grid = DrawWorld(world);
  const FastCorrelativeScanMatcher2D matcher(grid, FastCorrelativeScanMatcherOptions2D{});
  const common::Rigid2d truth(12.3, 5.4, 2.9);
  const sensor::PointCloud2d cloud = CastScan(world, truth, 180, 12.0);
  double score = 0.0;
  common::Rigid2d pose;
  const auto start = std::chrono::steady_clock::now();
  ASSERT_TRUE(matcher.MatchFullSubmap(cloud, 0.6, &score, &pose));
  std::printf("full-submap branch-and-bound match: %.1f ms, score %.3f\n",
              std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count(),
              score);
  EXPECT_LT((pose.translation() - truth.translation()).norm(), 0.05);
  EXPECT_LT(std::abs(common::NormalizeAngle(pose.angle_rad() - truth.angle_rad())), common::DegToRad(0.5));
}

TEST(FastCorrelativeScanMatcher2DTest, RejectsScanOfAnotherWorld) {
  const ProbabilityGrid grid = DrawWorld(MakeStructuredWorld(7));
  const FastCorrelativeScanMatcherOptions2D options;
  const FastCorrelativeScanMatcher2D matcher(grid, options);
  const std::vector<Segment> other = MakeStructuredWorld(99);
  const common::Rigid2d truth(8.0, 9.0, 1.0);
  double score = 0.0;
  common::Rigid2d pose;
  EXPECT_FALSE(matcher.Match(truth, CastScan(other, truth, 180, 12.0), 0.7, &score, &pose));
  EXPECT_FALSE(matcher.Match(truth, {}, 0.0, &score, &pose));
}

TEST(FastCorrelativeScanMatcher2DTest, ScoreAtIsTheScoreMatchGivesThePoseItFinds) {
  const std::vector<Segment> world = MakeStructuredWorld(7);
  const ProbabilityGrid grid = DrawWorld(world);
  const FastCorrelativeScanMatcher2D matcher(grid, FastCorrelativeScanMatcherOptions2D{});
  const common::Rigid2d truth(8.0, 9.0, 1.0);
  const sensor::PointCloud2d cloud = CastScan(world, truth, 180, 12.0);
  double score = 0.0;
  common::Rigid2d pose;
  ASSERT_TRUE(matcher.Match(common::Rigid2d(8.3, 8.8, 1.05), cloud, 0.0, &score, &pose));
  // The same cells up to float rounding at cell borders.
  EXPECT_NEAR(matcher.ScoreAt(pose, cloud), score, 0.01);
  // Away from where the scan was taken it fits worse; with no points, not at all.
  EXPECT_LT(matcher.ScoreAt(common::Rigid2d(9.0, 9.0, 1.3), cloud), score - 0.1);
  EXPECT_EQ(matcher.ScoreAt(pose, {}), 0.0);
}

TEST(FastCorrelativeScanMatcher2DTest, OptionsValidation) {
  std::string error;
  FastCorrelativeScanMatcherOptions2D options;
  EXPECT_TRUE(options.IsValid(&error));
  options.branch_and_bound_depth = 0;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_FALSE(error.empty());
}

TEST(FastCorrelativeScanMatcher2DTest, ParsesOptionsAndRejectsOutOfRange) {
  std::string error;
  auto reader = common::ConfigReader::FromString("{linear_search_window_m: 5.0, angular_search_window_rad: 0.5, branch_and_bound_depth: 6, min_score: 0.6}", "test", &error);
  ASSERT_NE(reader, nullptr) << error;
  const auto options = ParseFastCorrelativeScanMatcherOptions2D(*reader);
  EXPECT_TRUE(reader->Finish(&error)) << error;
  EXPECT_EQ(options.linear_search_window_m, 5.0);
  EXPECT_EQ(options.angular_search_window_rad, 0.5);
  EXPECT_EQ(options.branch_and_bound_depth, 6);
  EXPECT_EQ(options.min_score, 0.6);
  EXPECT_EQ(options.translation_delta_cost_weight, 0.0);
  auto prior = common::ConfigReader::FromString(
      "{translation_delta_cost_weight: 0.4, rotation_delta_cost_weight: 2.0}", "prior.yaml", &error);
  ASSERT_NE(prior, nullptr) << error;
  const auto with_prior = ParseFastCorrelativeScanMatcherOptions2D(*prior);
  EXPECT_TRUE(prior->Finish(&error)) << error;
  EXPECT_EQ(with_prior.translation_delta_cost_weight, 0.4);
  EXPECT_EQ(with_prior.rotation_delta_cost_weight, 2.0);
  auto negative =
      common::ConfigReader::FromString("{rotation_delta_cost_weight: -1}", "neg.yaml", &error);
  ASSERT_NE(negative, nullptr) << error;
  ParseFastCorrelativeScanMatcherOptions2D(*negative);
  EXPECT_FALSE(negative->Finish(&error));
  auto bad = common::ConfigReader::FromString("{branch_and_bound_depth: 0}", "bad.yaml", &error);
  ASSERT_NE(bad, nullptr) << error;
  ParseFastCorrelativeScanMatcherOptions2D(*bad);
  EXPECT_FALSE(bad->Finish(&error));
  EXPECT_NE(error.find("bad.yaml"), std::string::npos) << error;
}

}  // namespace
}  // namespace mapping
}  // namespace fusemap
