#include "fusemap/io/lcm_output_conversions.h"

#include <cmath>

#include "fusemap/io/lcm_conversions.h"
#include "fusemap_lcm/cloud_region_t.hpp"
#include "fusemap_lcm/health_t.hpp"
#include "fusemap_lcm/loop_closure_t.hpp"
#include "fusemap_lcm/pose_t.hpp"
#include "fusemap_lcm/submap_list_t.hpp"
#include "lcm_wire.h"

namespace fusemap {
namespace io {
namespace {

void CopyVector(const Eigen::Vector3d& v, double* out) {
  for (int i = 0; i < 3; ++i) out[i] = v[i];
}

}  // namespace

std::vector<uint8_t> EncodePose(const PoseMessage& pose) {
  fusemap_lcm::pose_t msg{};
  msg.utime = StampToUtime(pose.stamp_s);
  CopyVector(pose.position_m, msg.pos);
  CopyVector(pose.velocity_mps, msg.vel);
  msg.orientation[0] = pose.orientation.w();
  msg.orientation[1] = pose.orientation.x();
  msg.orientation[2] = pose.orientation.y();
  msg.orientation[3] = pose.orientation.z();
  CopyVector(pose.rotation_rate_radps, msg.rotation_rate);
  CopyVector(pose.acceleration_mps2, msg.accel);
  return lcm_wire::Encode(msg);
}

std::vector<uint8_t> EncodePlanarPose(double stamp_s, const common::Rigid2d& T_map_tracking) {
  PoseMessage pose;
  pose.stamp_s = stamp_s;
  pose.position_m = Eigen::Vector3d(T_map_tracking.translation().x(),
                                    T_map_tracking.translation().y(), 0.0);
  // Built from the half angle rather than through Rigid3d, whose axis-angle conversion can
  // write -0.0 into x and y: the published bytes stay those fusemapd always sent.
  const double half_yaw = 0.5 * T_map_tracking.angle_rad();
  pose.orientation = Eigen::Quaterniond(std::cos(half_yaw), 0.0, 0.0, std::sin(half_yaw));
  return EncodePose(pose);
}

bool DecodePose(const void* data, int size, PoseMessage* out, std::string* error) {
  fusemap_lcm::pose_t msg;
  if (!lcm_wire::DecodeFixed(data, size, &msg, error)) return false;
  using lcm_wire::AllFinite;
  if (!AllFinite(msg.pos, 3) || !AllFinite(msg.vel, 3) || !AllFinite(msg.orientation, 4) ||
      !AllFinite(msg.rotation_rate, 3) || !AllFinite(msg.accel, 3)) {
    return lcm_wire::WireCursor::Fail("non-finite pose field", error);
  }
  out->stamp_s = UtimeToStamp(msg.utime);
  out->position_m = Eigen::Map<const Eigen::Vector3d>(msg.pos);
  out->velocity_mps = Eigen::Map<const Eigen::Vector3d>(msg.vel);
  out->orientation = Eigen::Quaterniond(msg.orientation[0], msg.orientation[1],
                                        msg.orientation[2], msg.orientation[3]);
  out->rotation_rate_radps = Eigen::Map<const Eigen::Vector3d>(msg.rotation_rate);
  out->acceleration_mps2 = Eigen::Map<const Eigen::Vector3d>(msg.accel);
  return true;
}

std::vector<uint8_t> EncodeSubmapList(double stamp_s,
                                      const pose_graph::PoseGraphSnapshot& snapshot) {
  fusemap_lcm::submap_list_t msg;
  msg.utime = StampToUtime(stamp_s);
  msg.solve_count = static_cast<int64_t>(snapshot.solve_count);
  msg.nsubmaps = static_cast<int32_t>(snapshot.T_map_submaps.size());
  for (const auto& T : snapshot.T_map_submaps) {
    msg.x.push_back(T.translation().x());
    msg.y.push_back(T.translation().y());
    msg.theta.push_back(T.angle_rad());
  }
  return lcm_wire::Encode(msg);
}

std::vector<uint8_t> EncodeLoopClosure(double stamp_s, int new_loop_closures,
                                       const pose_graph::PoseGraph2D::Stats& stats,
                                       int latest_node) {
  fusemap_lcm::loop_closure_t msg;
  msg.utime = StampToUtime(stamp_s);
  msg.new_loop_closures = new_loop_closures;
  msg.total_loop_closures = stats.loop_closures_found;
  msg.optimizations = stats.optimizations;
  msg.latest_node = latest_node;
  return lcm_wire::Encode(msg);
}

std::vector<uint8_t> EncodeHealth(double stamp_s, const HealthReport& report) {
  fusemap_lcm::health_t msg;
  msg.utime = StampToUtime(stamp_s);
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
  return lcm_wire::Encode(msg);
}

std::vector<uint8_t> EncodeCloudRegion(const CloudRegionUpdate& update) {
  fusemap_lcm::cloud_region_t msg;
  msg.utime = StampToUtime(update.stamp_s);
  msg.submap_id = update.submap_id;
  const Eigen::Vector3d t = update.T_map_submap.translation();
  const Eigen::Quaterniond q = update.T_map_submap.rotation();
  msg.T_map_submap.translation[0] = t.x();
  msg.T_map_submap.translation[1] = t.y();
  msg.T_map_submap.translation[2] = t.z();
  msg.T_map_submap.rotation[0] = q.w();
  msg.T_map_submap.rotation[1] = q.x();
  msg.T_map_submap.rotation[2] = q.y();
  msg.T_map_submap.rotation[3] = q.z();
  msg.total_points = static_cast<int32_t>(update.total_points);
  const cloud::ColorCloud& points = *update.points_submap;
  msg.npoints = static_cast<int32_t>(points.size());
  msg.xyz.reserve(points.size());
  msg.rgb.reserve(points.size());
  for (const cloud::ColorPoint& p : points) {
    msg.xyz.push_back({p.x, p.y, p.z});
    msg.rgb.push_back({p.r, p.g, p.b});
  }
  return lcm_wire::Encode(msg);
}

}  // namespace io
}  // namespace fusemap
