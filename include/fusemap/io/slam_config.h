#ifndef FUSEMAP_IO_SLAM_CONFIG_H_
#define FUSEMAP_IO_SLAM_CONFIG_H_

#include <string>

#include "fusemap/cloud/cloud_mapper.h"
#include "fusemap/common/config_reader.h"
#include "fusemap/io/lcm_conversions.h"
#include "fusemap/io/visual_loop_config.h"
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
  cloud::CloudMapperOptions cloud;  // RGB-D cloud binder; frames come on channels.rgbd
  VisualLoopConfig visual_loop;     // ORB visual loop checker on the same frames; off by default
};

// Reads the top-level keys channels, lidar, local_slam, global_slam, cloud and visual_loop from `reader`
// into *config. Problems are recorded in the reader (its Finish() reports them), so a caller
// may read top-level keys of its own (fusemapd's daemon:) from the same reader before that.
void ParseSlamConfig(common::ConfigReader& reader, SlamConfig* config);

// Top-level keys: channels, lidar, local_slam, global_slam, cloud, visual_loop. Unknown keys, wrong types and
// out-of-range values fail with file:line and the key.
bool LoadSlamConfig(const std::string& path, SlamConfig* config, std::string* error);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_SLAM_CONFIG_H_
