#include "fusemap/io/slam_config.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>

namespace fusemap {
namespace io {
namespace {

// A config file in the temp directory, removed when the test ends.
class TempConfig {
 public:
  explicit TempConfig(const std::string& text) {
    path_ = ::testing::TempDir() + "slam_config_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".yaml";
    std::ofstream(path_) << text;
  }
  ~TempConfig() { std::remove(path_.c_str()); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// carmen.yaml states the sensor only; the rest is the default profile.
TEST(SlamConfigTest, LoadsCarmenConfig) {
  SlamConfig config;
  std::string error;
  ASSERT_TRUE(LoadSlamConfig(std::string(FUSEMAP_SOURCE_DIR) + "/config/carmen.yaml", &config,
                             &error))
      << error;
  EXPECT_EQ(config.channels.lidar, "LIDAR");
  EXPECT_EQ(config.channels.odometry, "ODOMETRY");
  EXPECT_DOUBLE_EQ(config.lidar.range_max_m, 81.0);
  const auto& local = config.map_builder.local_slam;
  EXPECT_FALSE(local.use_imu);
  EXPECT_EQ(local.submaps.num_range_data, 35);
  EXPECT_FLOAT_EQ(local.range_gate.max_range_m, 30.f);
  EXPECT_DOUBLE_EQ(local.ceres_scan_matcher.occupied_space_weight, 10.0);
  EXPECT_TRUE(local.initial_branch_and_bound_match.enabled);
  EXPECT_TRUE(local.initial_branch_and_bound_match.only_at_window_edge);
  const auto& global = config.map_builder.global_slam;
  EXPECT_EQ(global.optimize_every_n_nodes, 35);
  EXPECT_DOUBLE_EQ(global.constraint_builder.loop_closure_translation_weight, 1.1e6);
  EXPECT_DOUBLE_EQ(global.constraint_builder.fast_correlative_scan_matcher.linear_search_window_m,
                   4.0);
  EXPECT_TRUE(config.map_builder.IsValid(&error)) << error;
}

SlamConfig LoadOrFail(const std::string& path) {
  SlamConfig config;
  std::string error;
  EXPECT_TRUE(LoadSlamConfig(path, &config, &error)) << error;
  return config;
}

#define EXPECT_SAME(field) EXPECT_EQ(profile.field, defaults.field) << #field

// config/default.yaml is the built-in defaults written out (issue 14): a profile that states only
// its sensor gets exactly what default.yaml lists.
TEST(SlamConfigTest, DefaultProfileEqualsTheBuiltInDefaults) {
  const TempConfig empty("{}\n");
  const SlamConfig built_in = LoadOrFail(empty.path());
  const SlamConfig file = LoadOrFail(std::string(FUSEMAP_SOURCE_DIR) + "/config/default.yaml");

  EXPECT_EQ(file.channels.lidar, built_in.channels.lidar);
  EXPECT_EQ(file.channels.odometry, built_in.channels.odometry);
  EXPECT_EQ(file.channels.imu, built_in.channels.imu);
  EXPECT_EQ(file.channels.rgbd, built_in.channels.rgbd);
  EXPECT_EQ(file.channels.pose, built_in.channels.pose);
  EXPECT_EQ(file.lidar.frame, built_in.lidar.frame);
  EXPECT_EQ(file.lidar.range_min_m, built_in.lidar.range_min_m);
  EXPECT_EQ(file.lidar.range_max_m, built_in.lidar.range_max_m);

  {
    const auto& profile = file.map_builder.local_slam;
    const auto& defaults = built_in.map_builder.local_slam;
    EXPECT_SAME(T_tracking_laser.x());
    EXPECT_SAME(T_tracking_laser.y());
    EXPECT_SAME(T_tracking_laser.angle_rad());
    EXPECT_SAME(range_gate.min_range_m);
    EXPECT_SAME(range_gate.max_range_m);
    EXPECT_SAME(range_gate.insert_misses);
    EXPECT_SAME(range_gate.missing_data_ray_length_m);
    EXPECT_SAME(voxel_filter_size_m);
    EXPECT_SAME(adaptive_voxel_filter.max_length_m);
    EXPECT_SAME(adaptive_voxel_filter.min_num_points);
    EXPECT_SAME(adaptive_voxel_filter.max_range_m);
    EXPECT_SAME(loop_closure_adaptive_voxel_filter.max_length_m);
    EXPECT_SAME(loop_closure_adaptive_voxel_filter.min_num_points);
    EXPECT_SAME(loop_closure_adaptive_voxel_filter.max_range_m);
    EXPECT_SAME(min_num_returns);
    EXPECT_SAME(initial_branch_and_bound_match.enabled);
    EXPECT_SAME(initial_branch_and_bound_match.only_at_window_edge);
    EXPECT_SAME(initial_branch_and_bound_match.min_rescore_gain);
    EXPECT_SAME(initial_branch_and_bound_match.matching_resolution_m);
    EXPECT_SAME(initial_branch_and_bound_match.unknown_probability);
    EXPECT_SAME(initial_branch_and_bound_match.unknown_padding_m);
    EXPECT_SAME(initial_branch_and_bound_match.refresh_every_n_insertions);
    EXPECT_SAME(initial_branch_and_bound_match.min_score_gain);
    EXPECT_SAME(initial_branch_and_bound_match.near_linear_search_window_m);
    EXPECT_SAME(initial_branch_and_bound_match.near_angular_search_window_rad);
    EXPECT_SAME(initial_branch_and_bound_match.fast_correlative_scan_matcher.linear_search_window_m);
    EXPECT_SAME(
        initial_branch_and_bound_match.fast_correlative_scan_matcher.angular_search_window_rad);
    EXPECT_SAME(initial_branch_and_bound_match.fast_correlative_scan_matcher.branch_and_bound_depth);
    EXPECT_SAME(initial_branch_and_bound_match.fast_correlative_scan_matcher.min_score);
    EXPECT_SAME(
        initial_branch_and_bound_match.fast_correlative_scan_matcher.translation_delta_cost_weight);
    EXPECT_SAME(
        initial_branch_and_bound_match.fast_correlative_scan_matcher.rotation_delta_cost_weight);
    EXPECT_SAME(use_online_correlative_scan_matching);
    EXPECT_SAME(real_time_correlative_scan_matcher.linear_search_window_m);
    EXPECT_SAME(real_time_correlative_scan_matcher.angular_search_window_rad);
    EXPECT_SAME(real_time_correlative_scan_matcher.translation_delta_cost_weight);
    EXPECT_SAME(real_time_correlative_scan_matcher.rotation_delta_cost_weight);
    EXPECT_SAME(real_time_correlative_scan_matcher.unknown_probability);
    EXPECT_SAME(adaptive_rotation_prior.enabled);
    EXPECT_SAME(adaptive_rotation_prior.weight_deg);
    EXPECT_SAME(adaptive_rotation_prior.min_weight);
    EXPECT_SAME(adaptive_rotation_prior.max_weight);
    EXPECT_SAME(adaptive_rotation_prior.window_scans);
    EXPECT_SAME(adaptive_rotation_prior.min_scans);
    EXPECT_SAME(ceres_scan_matcher.occupied_space_weight);
    EXPECT_SAME(ceres_scan_matcher.translation_weight);
    EXPECT_SAME(ceres_scan_matcher.rotation_weight);
    EXPECT_SAME(ceres_scan_matcher.max_num_iterations);
    EXPECT_SAME(ceres_scan_matcher.unknown_probability);
    EXPECT_SAME(motion_filter.max_time_s);
    EXPECT_SAME(motion_filter.max_distance_m);
    EXPECT_SAME(motion_filter.max_angle_rad);
    EXPECT_SAME(submaps.num_range_data);
    EXPECT_SAME(submaps.resolution_m);
    EXPECT_SAME(submaps.range_data_inserter.hit_probability);
    EXPECT_SAME(submaps.range_data_inserter.miss_probability);
    EXPECT_SAME(submaps.range_data_inserter.insert_free_space);
    EXPECT_SAME(use_odometry);
    EXPECT_SAME(use_imu);
    EXPECT_SAME(pose_queue_duration_s);
  }
  {
    const auto& profile = file.map_builder.global_slam;
    const auto& defaults = built_in.map_builder.global_slam;
    EXPECT_SAME(optimize_every_n_nodes);
    EXPECT_SAME(constraint_builder.sampling_ratio);
    EXPECT_SAME(constraint_builder.max_constraint_distance_m);
    EXPECT_SAME(constraint_builder.fast_correlative_scan_matcher.linear_search_window_m);
    EXPECT_SAME(constraint_builder.fast_correlative_scan_matcher.angular_search_window_rad);
    EXPECT_SAME(constraint_builder.fast_correlative_scan_matcher.branch_and_bound_depth);
    EXPECT_SAME(constraint_builder.fast_correlative_scan_matcher.min_score);
    EXPECT_SAME(constraint_builder.loop_closure_translation_weight);
    EXPECT_SAME(constraint_builder.loop_closure_rotation_weight);
    EXPECT_SAME(matcher_translation_weight);
    EXPECT_SAME(matcher_rotation_weight);
    EXPECT_SAME(local_slam_translation_weight);
    EXPECT_SAME(local_slam_rotation_weight);
    EXPECT_SAME(linked_unmeasured_weight_fraction);
    EXPECT_SAME(final_optimization_iterations);
    EXPECT_SAME(optimization.huber_scale);
    EXPECT_SAME(optimization.max_num_iterations);
    EXPECT_SAME(matcher_memory_budget_mb);
    EXPECT_SAME(max_pending_searches);
  }
}

#undef EXPECT_SAME

TEST(SlamConfigTest, EmptyFileGivesDefaults) {
  const TempConfig file("{}\n");
  SlamConfig config;
  std::string error;
  ASSERT_TRUE(LoadSlamConfig(file.path(), &config, &error)) << error;
  EXPECT_EQ(config.channels.pose, "SLAM_POSE");
  EXPECT_EQ(config.map_builder.global_slam.optimize_every_n_nodes,
            pose_graph::PoseGraphOptions2D().optimize_every_n_nodes);
}

TEST(SlamConfigTest, UnknownKeyNamesFileLineAndKeyPath) {
  const TempConfig file(
      "channels:\n"
      "  lidar: LIDAR\n"
      "local_slam:\n"
      "  submaps:\n"
      "    num_range_dta: 20\n");
  SlamConfig config;
  config.channels.lidar = "UNTOUCHED";
  std::string error;
  EXPECT_FALSE(LoadSlamConfig(file.path(), &config, &error));
  EXPECT_NE(error.find(file.path() + ":5"), std::string::npos) << error;
  EXPECT_NE(error.find("local_slam.submaps.num_range_dta"), std::string::npos) << error;
  EXPECT_NE(error.find("unknown"), std::string::npos) << error;
  EXPECT_EQ(config.channels.lidar, "UNTOUCHED");  // a failed load leaves the output alone
}

// A profile that sets one key of global_slam.optimization keeps the pose graph's own values for
// the others (they used to fall back to a plain SE(2) graph's, Huber 0.1 among them).
TEST(SlamConfigTest, OneOptimizationKeyKeepsThePoseGraphsOtherValues) {
  const TempConfig empty("{}\n");
  const SlamConfig built_in = LoadOrFail(empty.path());
  const TempConfig file(
      "global_slam:\n"
      "  optimization:\n"
      "    max_num_iterations: 7\n");
  const SlamConfig config = LoadOrFail(file.path());
  const pose_graph::OptimizationOptions& set = config.map_builder.global_slam.optimization;
  const pose_graph::OptimizationOptions& defaults = built_in.map_builder.global_slam.optimization;
  // The pose graph's Huber scale is its own, so a reset would show.
  ASSERT_NE(defaults.huber_scale, pose_graph::OptimizationOptions().huber_scale);
  EXPECT_EQ(set.max_num_iterations, 7);
  EXPECT_EQ(set.huber_scale, defaults.huber_scale);
  EXPECT_EQ(set.function_tolerance, defaults.function_tolerance);
}

TEST(SlamConfigTest, WrongTypeFails) {
  const TempConfig file(
      "global_slam:\n"
      "  optimize_every_n_nodes: often\n");
  SlamConfig config;
  std::string error;
  EXPECT_FALSE(LoadSlamConfig(file.path(), &config, &error));
  EXPECT_NE(error.find(file.path() + ":2"), std::string::npos) << error;
  EXPECT_NE(error.find("global_slam.optimize_every_n_nodes"), std::string::npos) << error;
  EXPECT_NE(error.find("wrong type"), std::string::npos) << error;
}

TEST(SlamConfigTest, OutOfRangeValueFails) {
  const TempConfig file(
      "lidar:\n"
      "  range_min_m: 5.0\n"
      "  range_max_m: 1.0\n");
  SlamConfig config;
  std::string error;
  EXPECT_FALSE(LoadSlamConfig(file.path(), &config, &error));
  EXPECT_NE(error.find("lidar.range_max_m"), std::string::npos) << error;
}

TEST(SlamConfigTest, MissingFileFails) {
  SlamConfig config;
  std::string error;
  EXPECT_FALSE(LoadSlamConfig("/nonexistent/fusemap.yaml", &config, &error));
  EXPECT_NE(error.find("/nonexistent/fusemap.yaml"), std::string::npos) << error;
}

// Issue 18, item 4: configs that hung (resolution .inf, a NaN in T_tracking_laser), ran out of
// memory (resolution 1e-9) or slipped through (max_time_s .nan) are refused, naming the key.
TEST(SlamConfigTest, AbsurdNumbersAreRefusedWithFileLineAndKey) {
  const struct {
    const char* yaml;
    const char* key;
  } cases[] = {
      {"local_slam:\n  submaps:\n    resolution_m: .inf\n", ":3: key 'local_slam.submaps.resolution_m'"},
      {"local_slam:\n  submaps:\n    resolution_m: 1e-9\n", ":3: key 'local_slam.submaps.resolution_m'"},
      {"local_slam:\n  submaps:\n    num_range_data: 2000000000\n",
       ":3: key 'local_slam.submaps.num_range_data'"},
      {"local_slam:\n  T_tracking_laser: [.nan, 0, 0]\n", ":2: key 'local_slam.T_tracking_laser'"},
      {"local_slam:\n  motion_filter:\n    max_time_s: .nan\n",
       ":3: key 'local_slam.motion_filter.max_time_s'"},
  };
  for (const auto& c : cases) {
    const TempConfig file(c.yaml);
    SlamConfig config;
    std::string error;
    EXPECT_FALSE(LoadSlamConfig(file.path(), &config, &error)) << c.yaml;
    EXPECT_NE(error.find(file.path() + c.key), std::string::npos) << c.yaml << "\n" << error;
  }
}

}  // namespace
}  // namespace io
}  // namespace fusemap
