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

TEST(SlamConfigTest, LoadsIntelConfig) {
  SlamConfig config;
  std::string error;
  ASSERT_TRUE(LoadSlamConfig(std::string(FUSEMAP_SOURCE_DIR) + "/config/intel.yaml", &config,
                             &error))
      << error;
  EXPECT_EQ(config.channels.lidar, "LIDAR");
  EXPECT_EQ(config.channels.odometry, "ODOMETRY");
  EXPECT_DOUBLE_EQ(config.lidar.range_max_m, 81.0);
  const auto& local = config.map_builder.local_slam;
  EXPECT_EQ(local.submaps.num_range_data, 35);
  EXPECT_FALSE(local.use_imu);
  EXPECT_FLOAT_EQ(local.range_gate.max_range_m, 30.f);
  EXPECT_DOUBLE_EQ(local.ceres_scan_matcher.occupied_space_weight, 10.0);
  const auto& global = config.map_builder.global_slam;
  EXPECT_EQ(global.optimize_every_n_nodes, 35);
  EXPECT_DOUBLE_EQ(global.constraint_builder.sampling_ratio, 0.3);
  EXPECT_DOUBLE_EQ(global.constraint_builder.loop_closure_translation_weight, 1.1e6);
  EXPECT_DOUBLE_EQ(global.constraint_builder.loop_closure_rotation_weight, 1e7);
  EXPECT_DOUBLE_EQ(global.constraint_builder.fast_correlative_scan_matcher.linear_search_window_m,
                   4.0);
  EXPECT_EQ(global.final_optimization_iterations, 200);
  EXPECT_TRUE(config.map_builder.IsValid(&error)) << error;
}

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
