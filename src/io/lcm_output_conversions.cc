#include "fusemap/io/lcm_output_conversions.h"

#include <cmath>
#include <string>
#include <utility>

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

using lcm_wire::WireCursor;

// Far above any real map or daemon; a larger count is a corrupt message.
constexpr int32_t kMaxSubmaps = 1000000;
constexpr int32_t kMaxHealthChannels = 1000;

// Checks the fingerprint and reads the count that follows `header_bytes` of fixed fields.
bool ReadCount(WireCursor* cursor, int64_t hash, const char* type, int header_bytes,
               int32_t max_count, int32_t* count, std::string* error) {
  int64_t fingerprint = 0;
  if (!cursor->ReadInt64(&fingerprint)) return WireCursor::Fail("truncated fingerprint", error);
  if (fingerprint != hash) {
    return WireCursor::Fail(std::string("fingerprint is not ") + type, error);
  }
  if (!cursor->Skip(header_bytes) || !cursor->ReadInt32(count)) {
    return WireCursor::Fail(std::string("truncated ") + type + " header", error);
  }
  if (*count < 0 || *count > max_count) {
    return WireCursor::Fail(std::string("absurd count ") + std::to_string(*count) + " in " + type,
                            error);
  }
  return true;
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
    return WireCursor::Fail("non-finite pose field", error);
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

bool DecodeSubmapList(const void* data, int size, double* stamp_s,
                      pose_graph::PoseGraphSnapshot* out, std::string* error) {
  using Msg = fusemap_lcm::submap_list_t;
  WireCursor cursor(data, size);
  int32_t n = 0;
  if (!ReadCount(&cursor, Msg::getHash(), Msg::getTypeName(), 16, kMaxSubmaps, &n, error)) {
    return false;
  }
  if (!cursor.Skip(3 * 8 * static_cast<int64_t>(n))) {
    return WireCursor::Fail("truncated submap_list_t poses", error);
  }
  if (!cursor.AtEnd(error)) return false;
  Msg msg;
  if (msg.decode(data, 0, size) != size) return WireCursor::Fail("decode failed", error);
  pose_graph::PoseGraphSnapshot snapshot;
  snapshot.solve_count = static_cast<std::uint64_t>(msg.solve_count);
  for (int i = 0; i < n; ++i) {
    const double pose[3] = {msg.x[i], msg.y[i], msg.theta[i]};
    if (!lcm_wire::AllFinite(pose, 3)) {
      return WireCursor::Fail("non-finite pose of submap " + std::to_string(i), error);
    }
    snapshot.T_map_submaps.emplace_back(msg.x[i], msg.y[i], msg.theta[i]);
  }
  *stamp_s = UtimeToStamp(msg.utime);
  *out = std::move(snapshot);
  return true;
}

std::vector<uint8_t> EncodeLoopClosure(double stamp_s, int new_loop_closures,
                                       const pose_graph::PoseGraph2D::Stats& stats,
                                       int latest_node, const LoopNote& note) {
  fusemap_lcm::loop_closure_t msg;
  msg.utime = StampToUtime(stamp_s);
  msg.new_loop_closures = new_loop_closures;
  msg.total_loop_closures = stats.loop_closures_found;
  msg.optimizations = stats.optimizations;
  msg.latest_node = latest_node;
  msg.source = note.source;
  msg.decision = note.decision;
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
  msg.pending_searches = report.pending_searches;
  msg.checkpoint_failures = report.checkpoint_failures;
  msg.time_resets = report.time_resets;
  msg.visual_keyframes = report.visual.keyframes;
  msg.visual_candidates = report.visual.candidates;
  msg.visual_verified = report.visual.verified;
  msg.visual_forced = report.visual.forced;
  msg.visual_overridden = report.visual.overridden;
  msg.visual_rejected = report.visual.rejected;
  msg.visual_queue_depth = report.visual.queue_depth;
  msg.visual_dropped_frames = report.visual.dropped_frames;
  return lcm_wire::Encode(msg);
}

bool DecodeHealth(const void* data, int size, double* stamp_s, HealthReport* out,
                  std::string* error) {
  using Msg = fusemap_lcm::health_t;
  WireCursor cursor(data, size);
  int32_t n = 0;
  if (!ReadCount(&cursor, Msg::getHash(), Msg::getTypeName(), 16, kMaxHealthChannels, &n,
                 error)) {
    return false;
  }
  for (int i = 0; i < n; ++i) {
    if (!cursor.SkipString()) return WireCursor::Fail("bad health_t channel name", error);
  }
  // received, dropped, malformed (int64) and queue_depth (int32) per channel; then three
  // latencies, rss_bytes, six graph counts, checkpoint_failures and time_resets, seven visual
  // counts (int32) and visual_dropped_frames.
  constexpr int kTailBytes = 3 * 8 + 8 + 6 * 4 + 4 + 8 + 7 * 4 + 8;
  if (!cursor.Skip((3 * 8 + 4) * static_cast<int64_t>(n)) || !cursor.Skip(kTailBytes)) {
    return WireCursor::Fail("truncated health_t", error);
  }
  if (!cursor.AtEnd(error)) return false;
  Msg msg;
  if (msg.decode(data, 0, size) != size) return WireCursor::Fail("decode failed", error);
  HealthReport report;
  report.uptime_s = msg.uptime_s;
  for (int i = 0; i < n; ++i) {
    HealthReport::Channel channel;
    channel.name = msg.channel[i];
    channel.received = msg.received[i];
    channel.dropped = msg.dropped[i];
    channel.malformed = msg.malformed[i];
    channel.queue_depth = msg.queue_depth[i];
    report.channels.push_back(std::move(channel));
  }
  report.latency.median_ms = msg.latency_median_ms;
  report.latency.p99_ms = msg.latency_p99_ms;
  report.latency.max_ms = msg.latency_max_ms;
  report.rss_bytes = msg.rss_bytes;
  report.nodes = msg.nodes;
  report.submaps = msg.submaps;
  report.constraints = msg.constraints;
  report.loop_closures = msg.loop_closures;
  report.optimizations = msg.optimizations;
  report.pending_searches = msg.pending_searches;
  report.checkpoint_failures = msg.checkpoint_failures;
  report.time_resets = msg.time_resets;
  report.visual.keyframes = msg.visual_keyframes;
  report.visual.candidates = msg.visual_candidates;
  report.visual.verified = msg.visual_verified;
  report.visual.forced = msg.visual_forced;
  report.visual.overridden = msg.visual_overridden;
  report.visual.rejected = msg.visual_rejected;
  report.visual.queue_depth = msg.visual_queue_depth;
  report.visual.dropped_frames = msg.visual_dropped_frames;
  *stamp_s = UtimeToStamp(msg.utime);
  *out = std::move(report);
  return true;
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
