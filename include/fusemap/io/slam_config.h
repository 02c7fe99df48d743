#ifndef FUSEMAP_IO_SLAM_CONFIG_H_
#define FUSEMAP_IO_SLAM_CONFIG_H_

#include <string>

#include "fusemap/io/lcm_conversions.h"
#include "fusemap/pose_graph/map_builder_2d.h"

namespace fusemap {
namespace io {

// LCM channel names; UPPER_SNAKE by the LCM ecosystem's convention, all configurable.
struct ChannelNames {
  std::string lidar = "LIDAR";
  std::string odometry = "ODOMETRY";
  std::string imu = "IMU";
  std::string rgbd = "RGBD";
  std::string pose = "SLAM_POSE";
};

// Everything one robot/dataset profile in config/*.yaml sets.
struct SlamConfig {
  ChannelNames channels;
  LidarChannelConfig lidar;
  pose_graph::MapBuilderOptions2D map_builder;
};

// Top-level keys: channels, lidar, local_slam, global_slam. Unknown keys, wrong types and
// out-of-range values fail with file:line and the key.
bool LoadSlamConfig(const std::string& path, SlamConfig* config, std::string* error);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_SLAM_CONFIG_H_
