#include "fusemap/daemon/lcm_publisher.h"

#include <cmath>
#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <utility>

#include "fusemap/io/lcm_conversions.h"
#include "fusemap_lcm/health_t.hpp"
#include "fusemap_lcm/loop_closure_t.hpp"
#include "fusemap_lcm/pose_t.hpp"
#include "fusemap_lcm/submap_list_t.hpp"

namespace fusemap {
namespace daemon {

LcmPublisher::LcmPublisher(lcm::LCM* lcm, OutputChannels channels, bool health_to_stderr)
    : lcm_(lcm), channels_(std::move(channels)), health_to_stderr_(health_to_stderr) {}

template <typename Msg>
void LcmPublisher::Send(const std::string& channel, const Msg& msg) {
  if (lcm_ == nullptr) return;
  if (lcm_->publish(channel, &msg) == 0) {
    ++published_;
  } else {
    ++failed_;
  }
}

void LcmPublisher::PublishPose(double stamp_s, const common::Rigid2d& T_map_tracking) {
  fusemap_lcm::pose_t msg{};
  msg.utime = io::StampToUtime(stamp_s);
  msg.pos[0] = T_map_tracking.translation().x();
  msg.pos[1] = T_map_tracking.translation().y();
  const double half_yaw = 0.5 * T_map_tracking.angle_rad();
  msg.orientation[0] = std::cos(half_yaw);
  msg.orientation[3] = std::sin(half_yaw);
  Send(channels_.pose, msg);
}

void LcmPublisher::PublishSubmapList(double stamp_s,
                                     const pose_graph::PoseGraphSnapshot& snapshot) {
  fusemap_lcm::submap_list_t msg;
  msg.utime = io::StampToUtime(stamp_s);
  msg.solve_count = static_cast<int64_t>(snapshot.solve_count);
  msg.nsubmaps = static_cast<int32_t>(snapshot.T_map_submaps.size());
  for (const auto& T : snapshot.T_map_submaps) {
    msg.x.push_back(T.translation().x());
    msg.y.push_back(T.translation().y());
    msg.theta.push_back(T.angle_rad());
  }
  Send(channels_.submap_list, msg);
}

void LcmPublisher::PublishLoopClosure(double stamp_s, int new_loop_closures,
                                      const pose_graph::PoseGraph2D::Stats& stats,
                                      int latest_node) {
  fusemap_lcm::loop_closure_t msg;
  msg.utime = io::StampToUtime(stamp_s);
  msg.new_loop_closures = new_loop_closures;
  msg.total_loop_closures = stats.loop_closures_found;
  msg.optimizations = stats.optimizations;
  msg.latest_node = latest_node;
  Send(channels_.loop_closure, msg);
}

void LcmPublisher::PublishHealth(double stamp_s, const HealthReport& report) {
  fusemap_lcm::health_t msg;
  msg.utime = io::StampToUtime(stamp_s);
  msg.uptime_s = report.uptime_s;
  msg.nchannels = static_cast<int32_t>(report.channels.size());
  for (const auto& c : report.channels) {
    msg.channel.push_back(c.name);
    msg.received.push_back(c.received);
    msg.dropped.push_back(c.dropped);
    msg.malformed.push_back(c.malformed);
    msg.queue_depth.push_back(c.queue_depth);
  }
  msg.latency_median_ms = report.latency.median_ms;
  msg.latency_p99_ms = report.latency.p99_ms;
  msg.latency_max_ms = report.latency.max_ms;
  msg.rss_bytes = report.rss_bytes;
  msg.nodes = report.nodes;
  msg.submaps = report.submaps;
  msg.constraints = report.constraints;
  msg.loop_closures = report.loop_closures;
  msg.optimizations = report.optimizations;
  msg.checkpoint_failures = report.checkpoint_failures;
  msg.time_resets = report.time_resets;
  Send(channels_.health, msg);
  if (health_to_stderr_) {
    std::fprintf(stderr, "fusemapd: t=%.1f %s\n", stamp_s, FormatHealth(report).c_str());
  }
}

}  // namespace daemon
}  // namespace fusemap
