#include "fusemap/daemon/daemon_options.h"

namespace fusemap {
namespace daemon {

bool DaemonOptions::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error != nullptr) *error = message;
    return false;
  };
  if (submap_list_channel.empty() || loop_closure_channel.empty() ||
      health_channel.empty() || cloud_region_channel.empty()) {
    return fail("output channel names must not be empty");
  }
  if (sensor_queue_size < 1 || rgbd_queue_size < 1) return fail("queue sizes must be >= 1");
  if (!(submap_list_rate_hz > 0.0) || !(health_rate_hz > 0.0)) return fail("rates must be > 0");
  if (!(max_future_s > 0.0)) return fail("max_future_s must be > 0");
  if (!(max_nonfinite_range_fraction >= 0.0 && max_nonfinite_range_fraction <= 1.0)) {
    return fail("max_nonfinite_range_fraction must be in [0, 1]");
  }
  if (max_message_bytes < 1024) return fail("max_message_bytes must be >= 1024");
  if (max_image_pixels < 1) return fail("max_image_pixels must be >= 1");
  if (!(bad_message_log_interval_s >= 0.0)) return fail("bad_message_log_interval_s must be >= 0");
  if (!(checkpoint_period_s >= 0.0)) return fail("checkpoint_period_s must be >= 0");
  if (!stamp_filter().IsValid(error)) return false;
  if (!(release_memory_period_s >= 0.0)) return fail("release_memory_period_s must be >= 0");
  return true;
}

sensor::StampFilterOptions DaemonOptions::stamp_filter() const {
  sensor::StampFilterOptions options;
  options.max_jump_s = max_stamp_jump_s;
  options.time_reset_threshold_s = time_reset_threshold_s;
  options.max_time_reset_s = max_time_reset_s;
  return options;
}

DaemonOptions ParseDaemonOptions(common::ConfigReader& reader) {
  DaemonOptions options;
  reader.Get("submap_list_channel", &options.submap_list_channel);
  reader.Get("loop_closure_channel", &options.loop_closure_channel);
  reader.Get("health_channel", &options.health_channel);
  reader.Get("cloud_region_channel", &options.cloud_region_channel);
  reader.Get("sensor_queue_size", &options.sensor_queue_size);
  reader.Get("rgbd_queue_size", &options.rgbd_queue_size);
  reader.Get("submap_list_rate_hz", &options.submap_list_rate_hz);
  reader.Get("health_rate_hz", &options.health_rate_hz);
  reader.Get("max_future_s", &options.max_future_s);
  reader.Get("max_nonfinite_range_fraction", &options.max_nonfinite_range_fraction);
  reader.Get("max_message_bytes", &options.max_message_bytes);
  reader.Get("max_image_pixels", &options.max_image_pixels);
  reader.Get("bad_message_log_interval_s", &options.bad_message_log_interval_s);
  reader.Get("checkpoint_period_s", &options.checkpoint_period_s);
  reader.Get("time_reset_threshold_s", &options.time_reset_threshold_s);
  reader.Get("max_stamp_jump_s", &options.max_stamp_jump_s);
  reader.Get("max_time_reset_s", &options.max_time_reset_s);
  reader.Get("release_memory_period_s", &options.release_memory_period_s);
  std::string error;
  if (!options.IsValid(&error)) reader.AddError("daemon", error);
  return options;
}

bool LoadDaemonConfig(const std::string& path, io::SlamConfig* slam, DaemonOptions* daemon,
                      std::string* error) {
  auto reader = common::ConfigReader::FromFile(path, error);
  if (!reader) return false;
  io::SlamConfig result;
  io::ParseSlamConfig(*reader, &result);
  const DaemonOptions daemon_options = ParseDaemonOptions(reader->Child("daemon"));
  if (!reader->Finish(error)) return false;
  *slam = result;
  *daemon = daemon_options;
  return true;
}

}  // namespace daemon
}  // namespace fusemap
