#include "fusemap/daemon/daemon_options.h"

namespace fusemap {
namespace daemon {

void DaemonOptions::Check(common::OptionChecker* check) const {
  check->Require(!submap_list_channel.empty(), "submap_list_channel", "must not be empty");
  check->Require(!loop_closure_channel.empty(), "loop_closure_channel", "must not be empty");
  check->Require(!health_channel.empty(), "health_channel", "must not be empty");
  check->Require(!cloud_region_channel.empty(), "cloud_region_channel", "must not be empty");
  check->Require(sensor_queue_size >= 1, "sensor_queue_size", "must be >= 1");
  check->Require(rgbd_queue_size >= 1, "rgbd_queue_size", "must be >= 1");
  // The engine turns periods and rates into std::chrono durations (int64 ns, ~292 years): bounded
  // so that the conversion and the deadlines after it fit; a year, or a million per second, is
  // beyond any use.
  constexpr double kMaxPeriod_s = 365.0 * 86400.0;
  constexpr double kMinRate_hz = 1e-6;
  constexpr double kMaxRate_hz = 1000.0;
  const char* const period_range = "must be in [0, 31536000]";  // kMaxPeriod_s
  const char* const rate_range = "must be in [1e-06, 1000]";    // kMinRate_hz, kMaxRate_hz
  check->Require(submap_list_rate_hz >= kMinRate_hz && submap_list_rate_hz <= kMaxRate_hz,
                 "submap_list_rate_hz", rate_range);
  check->Require(health_rate_hz >= kMinRate_hz && health_rate_hz <= kMaxRate_hz, "health_rate_hz",
                 rate_range);
  check->Require(max_future_s > 0.0, "max_future_s", "must be > 0");
  check->Require(max_nonfinite_range_fraction >= 0.0 && max_nonfinite_range_fraction <= 1.0,
                 "max_nonfinite_range_fraction", "must be in [0, 1]");
  check->Require(max_message_bytes >= 1024, "max_message_bytes", "must be >= 1024");
  check->Require(max_image_pixels >= 1, "max_image_pixels", "must be >= 1");
  check->Require(bad_message_log_interval_s >= 0.0, "bad_message_log_interval_s", "must be >= 0");
  check->Require(checkpoint_period_s >= 0.0 && checkpoint_period_s <= kMaxPeriod_s,
                 "checkpoint_period_s", period_range);
  check->Require(release_memory_period_s >= 0.0 && release_memory_period_s <= kMaxPeriod_s,
                 "release_memory_period_s", period_range);
  check->Require(realtime_priority >= 0 && realtime_priority <= 99, "realtime_priority",
                 "must be in [0, 99]");
  // The stamp filter's rules, under the names its fields have in daemon:.
  common::OptionChecker stamps;
  stamp_filter().Check(&stamps);
  for (const auto& problem : stamps.problems()) {
    check->Require(false, problem.key == "max_jump_s" ? "max_stamp_jump_s" : problem.key,
                   problem.message);
  }
}

bool DaemonOptions::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
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
  reader.Get("realtime_priority", &options.realtime_priority);
  reader.CheckOptions(options);
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
