#include "fusemap/sim_log/sim_log.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>

#include "fusemap/io/lcm_conversions.h"
#include "fusemap/io/lcm_log.h"
#include "fusemap/io/lcm_output_conversions.h"
#include "fusemap/io/rgbd_conversions.h"
#include "fusemap/sim/world_loader.h"

namespace fusemap {
namespace sim_log {
namespace {

std::unique_ptr<sim::Simulation> SmallSimulation(uint64_t seed) {
  sim::World world;
  std::string error;
  EXPECT_TRUE(sim::LoadWorldFile(std::string(FUSEMAP_SOURCE_DIR) + "/data/worlds/hall.yaml", &world, &error));
  sim::SimulationOptions options;
  options.seed = seed;
  options.seconds = 0.5;
  options.rgbd.width = 160;
  options.rgbd.height = 120;
  options.rgbd.fx = options.rgbd.fy = 131.25;
  options.rgbd.cx = 79.5;
  options.rgbd.cy = 59.5;
  auto simulation = sim::Simulation::Create(std::move(world), options, &error);
  EXPECT_TRUE(simulation) << error;
  return simulation;
}

std::string TempPath(const std::string& name) {
  return "/tmp/fusemap_sim_log_test_" + std::to_string(::getpid()) + "_" + name;
}

std::string ReadAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST(SimLogTest, LogRoundTripsWithCountsPerChannel) {
  auto simulation = SmallSimulation(1);
  SimLogOptions options;
  options.log_path = TempPath("a.lcm");
  options.groundtruth_tum_path = TempPath("a.tum");
  SimLogSummary summary;
  std::string error;
  ASSERT_TRUE(WriteSimulationLog(*simulation, options, &summary, &error)) << error;
  // 0.5 s: ground truth 100 Hz, IMU 200 Hz, odometry 50 Hz, laser 25 Hz, RGB-D 10 Hz.
  const std::map<std::string, int64_t> expected = {
      {"GROUND_TRUTH", 50}, {"IMU", 100}, {"ODOMETRY", 25}, {"LIDAR", 13}, {"RGBD", 5}};
  EXPECT_EQ(summary.messages_per_channel, expected);

  io::LcmLogReader reader;
  ASSERT_TRUE(reader.Open(options.log_path, &error)) << error;
  std::map<std::string, int64_t> counts;
  io::LogEvent event;
  int64_t last_utime = 0;
  while (reader.Next(&event)) {
    ++counts[event.channel];
    EXPECT_GE(event.utime, last_utime);
    last_utime = event.utime;
    if (event.channel == "LIDAR") {
      sensor::LaserScan scan;
      ASSERT_TRUE(io::DecodeLaserScan(event.data.data(), static_cast<int>(event.data.size()),
                                      io::LidarChannelConfig(), &scan, &error)) << error;
      EXPECT_EQ(scan.ranges_m.size(), 811u);
    } else if (event.channel == "RGBD") {
      sensor::RgbdFrame frame;
      ASSERT_TRUE(io::DecodeRgbdFrame(event.data.data(), static_cast<int>(event.data.size()), &frame, &error)) << error;
      EXPECT_EQ(frame.color_intrinsics.width, 160);
      EXPECT_EQ(io::StampToUtime(frame.stamp_s), event.utime);
    } else if (event.channel == "GROUND_TRUTH") {
      io::PoseMessage pose;
      ASSERT_TRUE(io::DecodePose(event.data.data(), static_cast<int>(event.data.size()), &pose,
                                 &error)) << error;
      EXPECT_EQ(io::StampToUtime(pose.stamp_s), event.utime);
      EXPECT_EQ(pose.position_m.z(), 0.0);
      EXPECT_NEAR(pose.orientation.norm(), 1.0, 1e-12);
    }
  }
  EXPECT_EQ(counts, expected);
  std::remove(options.log_path.c_str());
  std::remove(options.groundtruth_tum_path.c_str());
}

TEST(SimLogTest, SameSeedSameBytesRegardlessOfThreads) {
  std::string error;
  SimLogSummary summary;
  std::string bytes[3];
  const uint64_t seeds[3] = {5, 5, 6};
  common::ThreadPool pool(2);
  for (int i = 0; i < 3; ++i) {
    SimLogOptions options;
    options.log_path = TempPath("d" + std::to_string(i) + ".lcm");
    // Run 0 renders on this thread, runs 1 and 2 on two pool threads, 3 frames at a time.
    options.render_executor = i == 0 ? nullptr : &pool;
    options.render_batch = i == 0 ? 8 : 3;
    ASSERT_TRUE(WriteSimulationLog(*SmallSimulation(seeds[i]), options, &summary, &error)) << error;
    bytes[i] = ReadAll(options.log_path);
    std::remove(options.log_path.c_str());
  }
  ASSERT_GT(bytes[0].size(), 10000u);
  EXPECT_TRUE(bytes[0] == bytes[1]) << "same seed, different thread count: logs differ";
  EXPECT_FALSE(bytes[0] == bytes[2]) << "different seeds gave identical logs";
}

}  // namespace
}  // namespace sim_log
}  // namespace fusemap
