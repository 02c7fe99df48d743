#include "fusemap/daemon/daemon_options.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace fusemap {
namespace daemon {
namespace {

std::string WriteTemp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "/" + name;
  std::ofstream(path) << text;
  return path;
}

TEST(DaemonOptionsTest, ProfileWithoutDaemonKeyUsesDefaults) {
  io::SlamConfig slam;
  DaemonOptions options;
  std::string error;
  ASSERT_TRUE(LoadDaemonConfig(std::string(FUSEMAP_SOURCE_DIR) + "/config/sim.yaml", &slam,
                               &options, &error))
      << error;
  EXPECT_EQ(slam.channels.lidar, "LIDAR");
  EXPECT_EQ(options.sensor_queue_size, DaemonOptions().sensor_queue_size);
  EXPECT_EQ(options.health_channel, "FUSEMAP_HEALTH");
  EXPECT_EQ(options.cloud_region_channel, "FUSEMAP_CLOUD_REGION");
}

TEST(DaemonOptionsTest, DaemonYamlLoadsAndKeepsSimSlamOptions) {
  io::SlamConfig slam, sim;
  DaemonOptions options, unused;
  std::string error;
  const std::string dir = std::string(FUSEMAP_SOURCE_DIR) + "/config/";
  ASSERT_TRUE(LoadDaemonConfig(dir + "daemon.yaml", &slam, &options, &error)) << error;
  ASSERT_TRUE(LoadDaemonConfig(dir + "sim.yaml", &sim, &unused, &error)) << error;
  EXPECT_EQ(slam.channels.pose, "FUSEMAP_POSE");
  EXPECT_DOUBLE_EQ(options.checkpoint_period_s, 60.0);
  // The SLAM part is sim.yaml's: spot-check values that differ from the struct defaults.
  EXPECT_EQ(slam.map_builder.global_slam.optimize_every_n_nodes,
            sim.map_builder.global_slam.optimize_every_n_nodes);
  EXPECT_EQ(slam.map_builder.local_slam.submaps.num_range_data,
            sim.map_builder.local_slam.submaps.num_range_data);
  EXPECT_FLOAT_EQ(slam.lidar.range_max_m, sim.lidar.range_max_m);
}

TEST(DaemonOptionsTest, DaemonYamlSlamPartIsSimYamlVerbatim) {
  // config/daemon.yaml repeats config/sim.yaml (YAML has no include); catch drift here.
  const std::string dir = std::string(FUSEMAP_SOURCE_DIR) + "/config/";
  YAML::Node daemon = YAML::LoadFile(dir + "daemon.yaml");
  YAML::Node sim = YAML::LoadFile(dir + "sim.yaml");
  daemon.remove("daemon");
  daemon["channels"].remove("rgbd");
  daemon["channels"].remove("pose");
  YAML::Emitter a, b;
  a << daemon;
  b << sim;
  EXPECT_EQ(std::string(a.c_str()), std::string(b.c_str()));
}

TEST(DaemonOptionsTest, UnknownAndOutOfRangeDaemonKeysFailWithKey) {
  io::SlamConfig slam;
  DaemonOptions options;
  std::string error;
  EXPECT_FALSE(LoadDaemonConfig(WriteTemp("typo.yaml", "daemon:\n  sensor_queue_sise: 3\n"),
                                &slam, &options, &error));
  EXPECT_NE(error.find("sensor_queue_sise"), std::string::npos) << error;
  EXPECT_FALSE(LoadDaemonConfig(WriteTemp("range.yaml", "daemon:\n  sensor_queue_size: 0\n"),
                                &slam, &options, &error));
  EXPECT_NE(error.find("range.yaml:2: key 'daemon.sensor_queue_size': must be >= 1"),
            std::string::npos)
      << error;
  ASSERT_TRUE(LoadDaemonConfig(WriteTemp("ok.yaml", "daemon:\n  rgbd_queue_size: 9\n"), &slam,
                               &options, &error))
      << error;
  EXPECT_EQ(options.rgbd_queue_size, 9);
  ASSERT_TRUE(LoadDaemonConfig(WriteTemp("cloud.yaml", "daemon:\n  cloud_region_channel: CLOUD\n"),
                               &slam, &options, &error))
      << error;
  EXPECT_EQ(options.cloud_region_channel, "CLOUD");
  EXPECT_FALSE(LoadDaemonConfig(WriteTemp("empty.yaml", "daemon:\n  cloud_region_channel: ''\n"),
                                &slam, &options, &error));
  EXPECT_NE(error.find("empty.yaml:2: key 'daemon.cloud_region_channel': must not be empty"),
            std::string::npos)
      << error;
}

TEST(DaemonOptionsTest, RealtimePriorityIsOffByDefaultAndChecked) {
  EXPECT_EQ(DaemonOptions().realtime_priority, 0);
  io::SlamConfig slam;
  DaemonOptions options;
  std::string error;
  ASSERT_TRUE(LoadDaemonConfig(WriteTemp("rt.yaml", "daemon:\n  realtime_priority: 20\n"), &slam,
                               &options, &error))
      << error;
  EXPECT_EQ(options.realtime_priority, 20);
  EXPECT_FALSE(LoadDaemonConfig(WriteTemp("rt100.yaml", "daemon:\n  realtime_priority: 100\n"),
                                &slam, &options, &error));
  EXPECT_NE(error.find("rt100.yaml:2: key 'daemon.realtime_priority': must be in [0, 99]"),
            std::string::npos)
      << error;
}

// The engine turns these into std::chrono durations (int64 ns): 1e300 s or a rate of 1e-300 Hz
// overflowed that conversion (undefined behaviour), and a rate of 1e9 Hz made the report thread
// spin. (Non-finite values are refused by the reader.)
TEST(DaemonOptionsTest, PeriodsAndRatesAreBoundedSoTheirDurationsFit) {
  io::SlamConfig slam;
  DaemonOptions options;
  std::string error;
  const std::vector<std::pair<std::string, std::string>> refused = {
      {"release_memory_period_s: 1e300",
       "key 'daemon.release_memory_period_s': must be in [0, 31536000]"},
      {"checkpoint_period_s: 1e300", "key 'daemon.checkpoint_period_s': must be in [0, 31536000]"},
      {"submap_list_rate_hz: 1e-300", "key 'daemon.submap_list_rate_hz': must be in [1e-06, 1000]"},
      {"health_rate_hz: 1e9", "key 'daemon.health_rate_hz': must be in [1e-06, 1000]"},
  };
  for (const auto& [line, message] : refused) {
    EXPECT_FALSE(LoadDaemonConfig(WriteTemp("bound.yaml", "daemon:\n  " + line + "\n"), &slam,
                                  &options, &error))
        << line;
    EXPECT_NE(error.find(message), std::string::npos) << line << ": " << error;
  }
  ASSERT_TRUE(LoadDaemonConfig(WriteTemp("edge.yaml",
                                         "daemon:\n  release_memory_period_s: 31536000\n"
                                         "  checkpoint_period_s: 0\n  health_rate_hz: 1e-6\n"
                                         "  submap_list_rate_hz: 1000\n"),
                               &slam, &options, &error))
      << error;
  EXPECT_EQ(options.release_memory_period_s, 31536000.0);
  EXPECT_EQ(options.submap_list_rate_hz, 1000.0);
}

}  // namespace
}  // namespace daemon
}  // namespace fusemap
