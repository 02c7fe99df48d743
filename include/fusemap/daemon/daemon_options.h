#ifndef FUSEMAP_DAEMON_DAEMON_OPTIONS_H_
#define FUSEMAP_DAEMON_DAEMON_OPTIONS_H_

#include <string>

#include "fusemap/common/config_reader.h"
#include "fusemap/io/slam_config.h"
#include "fusemap/sensor/stamp_filter.h"

namespace fusemap {
namespace daemon {

// fusemapd's own settings: the `daemon:` key of the same YAML file as the SLAM profile, so a
// profile without that key runs with these defaults.
struct DaemonOptions {
  // Output channels (the pose goes on the profile's channels.pose).
  std::string submap_list_channel = "FUSEMAP_SUBMAPS";
  std::string loop_closure_channel = "FUSEMAP_LOOP_CLOSURE";
  std::string health_channel = "FUSEMAP_HEALTH";
  std::string cloud_region_channel = "FUSEMAP_CLOUD_REGION";
  // Laser, odometry and IMU share one queue so their order is kept (the offline runner's order).
  int sensor_queue_size = 400;
  int rgbd_queue_size = 4;
  double submap_list_rate_hz = 5.0;
  double health_rate_hz = 1.0;
  // Messages stamped further than this ahead of the wall clock are rejected (live sources only).
  double max_future_s = 5.0;
  // Scans with a larger share of NaN/inf ranges are rejected as broken.
  double max_nonfinite_range_fraction = 0.5;
  int max_message_bytes = 32 << 20;
  // RGB-D frames whose colour or depth image has more pixels are rejected before decoding
  // (the camera bound; 4096 x 4096 by default, above any current RGB-D camera).
  int max_image_pixels = 4096 * 4096;
  // Seconds between malformed-message log lines of one kind.
  double bad_message_log_interval_s = 10.0;
  // Seconds between checkpoints; 0 = only at shutdown.
  double checkpoint_period_s = 60.0;
  // A laser stamp this much before the previous one is a time reset (looping log player,
  // clock set back): a new time base instead of a drop (see Intake). 0 = never.
  double time_reset_threshold_s = 5.0;
  // A stamp this far ahead of every channel's newest is held until the channel's next message
  // confirms the jump (else dropped as an outlier); a laser jump back by more than
  // max_time_reset_s is held the same way instead of being a time reset (see Intake).
  double max_stamp_jump_s = 60.0;
  double max_time_reset_s = 30.0 * 86400.0;
  // Seconds between handing freed heap pages back to the system. glibc keeps what trimmed
  // submaps and checkpoint buffers released, spread over its per-thread arenas, so without
  // this the resident size creeps up over hours although the live heap is flat. 0 = never.
  double release_memory_period_s = 10.0;
  // SCHED_FIFO priority (1-99) for the threads between a scan's receipt and its pose: the LCM
  // handler, the SLAM thread and the publisher. They then preempt every other thread at
  // wake-up, so that global SLAM's workers and the RGB-D and visual threads never delay a pose
  // on a busy machine. Needs root, CAP_SYS_NICE or RLIMIT_RTPRIO; refused, it is logged once
  // and those threads run at normal priority. 0 = normal scheduling.
  int realtime_priority = 0;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
  sensor::StampFilterOptions stamp_filter() const;
};

// Keys: as the field names.
DaemonOptions ParseDaemonOptions(common::ConfigReader& reader);

// Loads a SLAM profile (keys of io::LoadSlamConfig) plus the optional `daemon:` key. Unknown
// keys anywhere fail with file:line and the key.
bool LoadDaemonConfig(const std::string& path, io::SlamConfig* slam, DaemonOptions* daemon,
                      std::string* error);

}  // namespace daemon
}  // namespace fusemap

#endif  // FUSEMAP_DAEMON_DAEMON_OPTIONS_H_
