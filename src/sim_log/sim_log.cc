#include "fusemap/sim_log/sim_log.h"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include "fusemap/eval/trajectory.h"
#include "fusemap/io/lcm_conversions.h"
#include "fusemap/io/lcm_log.h"
#include "fusemap/io/lcm_output_conversions.h"
#include "fusemap/io/tum_trajectory.h"

namespace fusemap {
namespace sim_log {
namespace {

enum Channel { kGroundTruth = 0, kOdometry, kImu, kLidar, kRgbd, kNumChannels };
const char* const kChannelNames[kNumChannels] = {kGroundTruthChannel, kOdometryChannel, kImuChannel,
                                                 kLidarChannel, kRgbdChannel};

struct Event {
  int64_t utime;
  int channel;
  int index;
  bool operator<(const Event& o) const {
    return std::tie(utime, channel, index) < std::tie(o.utime, o.channel, o.index);
  }
};

io::PoseMessage GroundTruthMessage(const sim::RobotState& s, double stamp_s) {
  io::PoseMessage msg;
  msg.stamp_s = stamp_s;
  const common::Rigid3d pose = common::Rigid3d::FromRigid2d(s.T_world_base);
  const double yaw = s.T_world_base.angle_rad();
  msg.position_m = pose.translation();
  msg.velocity_mps = Eigen::Vector3d(s.speed_mps * std::cos(yaw),  // World frame.
                                     s.speed_mps * std::sin(yaw), 0.0);
  msg.orientation = pose.rotation();
  msg.rotation_rate_radps = Eigen::Vector3d(0.0, 0.0, s.yaw_rate_radps);
  // Body frame, without gravity.
  msg.acceleration_mps2 =
      Eigen::Vector3d(s.forward_accel_mps2, s.speed_mps * s.yaw_rate_radps, 0.0);
  return msg;
}

// Renders and encodes RGB-D frames [first, first + out->size()) on `executor` (null: here).
bool RenderBatch(const sim::Simulation& simulation, int first, common::Executor* executor,
                 const io::RgbdEncodeOptions& encoding, std::vector<std::vector<uint8_t>>* out,
                 std::string* error) {
  const int n = static_cast<int>(out->size());
  std::vector<std::string> errors(n);
  auto render = [&](int i) {
    const sensor::RgbdFrame frame = simulation.Rgbd(first + i);
    io::EncodeRgbdFrame(frame, encoding, &(*out)[i], &errors[i]);
  };
  for (int i = 0; i < n; ++i) {
    // The log's first frame here even with an executor: OpenCV fills its codec registry at the
    // first cv::imencode, behind a static guard that ThreadSanitizer cannot see in the
    // uninstrumented library; filled before the workers start, later encodes only read it.
    if (executor == nullptr || first + i == 0) {
      render(i);
    } else {
      executor->Schedule([&render, i] { render(i); });
    }
  }
  if (executor != nullptr) executor->WaitIdle();
  for (const std::string& e : errors) {
    if (!e.empty()) {
      *error = "RGB-D encoding: " + e;
      return false;
    }
  }
  return true;
}

}  // namespace

bool WriteSimulationLog(const sim::Simulation& simulation, const SimLogOptions& options,
                        SimLogSummary* summary, std::string* error) {
  const sim::SimulationOptions& so = simulation.options();
  const double rates[kNumChannels] = {so.ground_truth_rate_hz, so.odometry.rate_hz, so.imu.rate_hz,
                                      so.laser.rate_hz, so.rgbd_enabled ? so.rgbd.rate_hz : 0.0};
  std::vector<Event> events;
  for (int c = 0; c < kNumChannels; ++c) {
    if (rates[c] <= 0.0) continue;
    const int count = sim::Simulation::Count(rates[c], so.seconds);
    for (int i = 0; i < count; ++i) {
      events.push_back(Event{io::StampToUtime(simulation.Stamp(i / rates[c])), c, i});
    }
  }
  std::sort(events.begin(), events.end());

  io::LcmLogWriter writer;
  if (!writer.Open(options.log_path, error)) return false;
  sim::OdometrySimulator odometry = simulation.MakeOdometrySimulator();
  sim::ImuSimulator imu = simulation.MakeImuSimulator();
  eval::Trajectory groundtruth;
  const int batch_size = std::max(1, options.render_batch);
  std::vector<std::vector<uint8_t>> rgbd_batch;
  int rgbd_first = 0;
  *summary = SimLogSummary();
  int64_t written = 0;
  double next_progress_s = 0.0;

  for (const Event& event : events) {
    const double t = event.index / rates[event.channel];
    const double stamp = simulation.Stamp(t);
    std::vector<uint8_t> bytes;
    switch (event.channel) {
      case kGroundTruth: {
        const sim::RobotState state = simulation.Truth(t);
        bytes = io::EncodePose(GroundTruthMessage(state, stamp));
        groundtruth.push_back(eval::TimedPose3d{stamp, common::Rigid3d::FromRigid2d(state.T_world_base)});
        break;
      }
      case kOdometry: {
        double speed = 0.0, yaw_rate = 0.0;
        const sensor::OdometryData data = odometry.Step(stamp, simulation.Truth(t), &speed, &yaw_rate);
        bytes = io::EncodeOdometry(data, speed, yaw_rate);
        break;
      }
      case kImu:
        bytes = io::EncodeImu(imu.Step(stamp, simulation.Truth(t)));
        break;
      case kLidar:
        bytes = io::EncodeLaserScan(simulation.Laser(event.index));
        break;
      case kRgbd: {
        if (rgbd_batch.empty() || event.index >= rgbd_first + static_cast<int>(rgbd_batch.size())) {
          rgbd_first = event.index;
          const int total = sim::Simulation::Count(rates[kRgbd], so.seconds);
          rgbd_batch.assign(std::min(batch_size, total - rgbd_first), {});
          if (!RenderBatch(simulation, rgbd_first, options.render_executor, options.rgbd_encoding, &rgbd_batch, error)) {
            return false;
          }
        }
        bytes.swap(rgbd_batch[event.index - rgbd_first]);
        break;
      }
    }
    if (!writer.Write(kChannelNames[event.channel], event.utime, bytes.data(), static_cast<int>(bytes.size()))) {
      *error = options.log_path + ": write failed";
      return false;
    }
    ++written;
    ++summary->messages_per_channel[kChannelNames[event.channel]];
    summary->payload_bytes += static_cast<int64_t>(bytes.size());
    if (options.progress && t >= next_progress_s) {
      options.progress(t, written);
      next_progress_s = t + 1.0;
    }
  }
  writer.Close();
  summary->sim_seconds = so.seconds;
  if (!options.groundtruth_tum_path.empty() &&
      !io::WriteTumTrajectoryFile(options.groundtruth_tum_path, groundtruth, error)) {
    return false;
  }
  return true;
}

}  // namespace sim_log
}  // namespace fusemap
