#ifndef FUSEMAP_SIM_LOG_SIM_LOG_H_
#define FUSEMAP_SIM_LOG_SIM_LOG_H_

#include <cstdint>
#include <functional>
#include <map>
#include <string>

#include "fusemap/common/thread_pool.h"
#include "fusemap/io/rgbd_conversions.h"
#include "fusemap/sim/simulation.h"

namespace fusemap {
namespace sim_log {

// LCM channel names written by the simulator. The SLAM must never read kGroundTruthChannel.
constexpr char kLidarChannel[] = "LIDAR";
constexpr char kOdometryChannel[] = "ODOMETRY";
constexpr char kImuChannel[] = "IMU";
constexpr char kRgbdChannel[] = "RGBD";
constexpr char kGroundTruthChannel[] = "GROUND_TRUTH";

struct SimLogOptions {
  std::string log_path;
  std::string groundtruth_tum_path;  // Empty: no TUM file.
  // Renders RGB-D frames in parallel (null: on the caller's thread), `render_batch` frames at
  // a time; the output does not depend on either.
  common::Executor* render_executor = nullptr;
  int render_batch = 8;
  io::RgbdEncodeOptions rgbd_encoding;
  // Called now and then with the simulated time reached (seconds since the start).
  std::function<void(double sim_time_s, int64_t messages)> progress;
};

struct SimLogSummary {
  double sim_seconds = 0.0;
  std::map<std::string, int64_t> messages_per_channel;
  int64_t payload_bytes = 0;
};

// Writes every sensor message of `simulation` in stamp order (ties broken by channel) as an LCM
// log, and the ground truth as TUM. Output bytes depend only on the simulation (seed, world,
// options), not on the executor or timing.
bool WriteSimulationLog(const sim::Simulation& simulation, const SimLogOptions& options,
                        SimLogSummary* summary, std::string* error);

}  // namespace sim_log
}  // namespace fusemap

#endif  // FUSEMAP_SIM_LOG_SIM_LOG_H_
