#include "fusemap/io/slam_config.h"

#include "fusemap/common/config_reader.h"

namespace fusemap {
namespace io {

void ParseSlamConfig(common::ConfigReader& reader, SlamConfig* config) {
  SlamConfig result;
  common::ConfigReader& channels = reader.Child("channels");
  channels.Get("lidar", &result.channels.lidar);
  channels.Get("odometry", &result.channels.odometry);
  channels.Get("imu", &result.channels.imu);
  channels.Get("rgbd", &result.channels.rgbd);
  channels.Get("pose", &result.channels.pose);
  common::ConfigReader& lidar = reader.Child("lidar");
  lidar.Get("frame", &result.lidar.frame);
  lidar.Get("range_min_m", &result.lidar.range_min_m);
  lidar.Get("range_max_m", &result.lidar.range_max_m);
  lidar.CheckOptions(result.lidar);
  result.map_builder = pose_graph::ParseMapBuilderOptions2D(reader);
  result.cloud = cloud::ParseCloudMapperOptions(reader.Child("cloud"));
  result.visual_loop = ParseVisualLoopConfig(reader.Child("visual_loop"));
  *config = result;
}

bool LoadSlamConfig(const std::string& path, SlamConfig* config, std::string* error) {
  auto reader = common::ConfigReader::FromFile(path, error);
  if (!reader) return false;
  SlamConfig result;
  ParseSlamConfig(*reader, &result);
  if (!reader->Finish(error)) return false;
  *config = result;
  return true;
}

}  // namespace io
}  // namespace fusemap
