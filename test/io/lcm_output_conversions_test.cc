#include "fusemap/io/lcm_output_conversions.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "fusemap/io/lcm_conversions.h"
#include "fusemap_lcm/cloud_region_t.hpp"
#include "fusemap_lcm/health_t.hpp"
#include "fusemap_lcm/loop_closure_t.hpp"
#include "fusemap_lcm/pose_t.hpp"
#include "fusemap_lcm/submap_list_t.hpp"

namespace fusemap {
namespace io {
namespace {

// The encoders moved here from daemon/lcm_publisher.cc, daemon/cloud_region_publisher.cc and
// tools/sim/sim_log.cc. The Legacy* functions are those files' message building, kept
// verbatim so the tests prove the wire bytes did not change with the move.

template <class Msg>
std::vector<uint8_t> Bytes(const Msg& msg) {
  std::vector<uint8_t> bytes(msg.getEncodedSize());
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

template <class Msg>
Msg DecodeGenerated(const std::vector<uint8_t>& bytes) {
  Msg msg;
  EXPECT_EQ(msg.decode(bytes.data(), 0, static_cast<int>(bytes.size())),
            static_cast<int>(bytes.size()));
  return msg;
}

std::vector<uint8_t> LegacyPlanarPose(double stamp_s, const common::Rigid2d& T_map_tracking) {
  fusemap_lcm::pose_t msg{};
  msg.utime = StampToUtime(stamp_s);
  msg.pos[0] = T_map_tracking.translation().x();
  msg.pos[1] = T_map_tracking.translation().y();
  const double half_yaw = 0.5 * T_map_tracking.angle_rad();
  msg.orientation[0] = std::cos(half_yaw);
  msg.orientation[3] = std::sin(half_yaw);
  return Bytes(msg);
}

// The simulator's ground truth, with RobotState's fields as arguments.
std::vector<uint8_t> LegacyGroundTruth(int64_t utime, const common::Rigid2d& T_world_base,
                                       double speed_mps, double yaw_rate_radps,
                                       double forward_accel_mps2) {
  fusemap_lcm::pose_t msg;
  msg.utime = utime;
  const common::Rigid3d pose = common::Rigid3d::FromRigid2d(T_world_base);
  const double yaw = T_world_base.angle_rad();
  for (int i = 0; i < 3; ++i) msg.pos[i] = pose.translation()[i];
  msg.vel[0] = speed_mps * std::cos(yaw);
  msg.vel[1] = speed_mps * std::sin(yaw);
  msg.vel[2] = 0.0;
  msg.orientation[0] = pose.rotation().w();
  msg.orientation[1] = pose.rotation().x();
  msg.orientation[2] = pose.rotation().y();
  msg.orientation[3] = pose.rotation().z();
  msg.rotation_rate[0] = msg.rotation_rate[1] = 0.0;
  msg.rotation_rate[2] = yaw_rate_radps;
  msg.accel[0] = forward_accel_mps2;
  msg.accel[1] = speed_mps * yaw_rate_radps;
  msg.accel[2] = 0.0;
  return Bytes(msg);
}

std::vector<common::Rigid2d> TestPoses() {
  return {common::Rigid2d(0.0, 0.0, 0.0),        common::Rigid2d(1.25, -3.5, 1e-5),
          common::Rigid2d(-7.0, 2.0, -2.5),      common::Rigid2d(100.0, 1e-3, M_PI),
          common::Rigid2d(0.5, 0.25, -M_PI + 1e-9)};
}

TEST(LcmOutputConversionsTest, PlanarPoseBytesAreTheDaemonsFormerOnes) {
  double stamp_s = 1134863807.658747;
  for (const common::Rigid2d& T : TestPoses()) {
    EXPECT_EQ(EncodePlanarPose(stamp_s, T), LegacyPlanarPose(stamp_s, T)) << T.angle_rad();
    stamp_s += 0.04;
  }
}

TEST(LcmOutputConversionsTest, GroundTruthPoseBytesAreTheSimulatorsFormerOnes) {
  const double stamp_s = 12.345678;
  for (const common::Rigid2d& T : TestPoses()) {
    const double speed_mps = 0.8, yaw_rate_radps = -0.3, accel_mps2 = 0.1;
    const common::Rigid3d pose = common::Rigid3d::FromRigid2d(T);
    PoseMessage message;
    message.stamp_s = stamp_s;
    message.position_m = pose.translation();
    message.velocity_mps = Eigen::Vector3d(speed_mps * std::cos(T.angle_rad()),
                                           speed_mps * std::sin(T.angle_rad()), 0.0);
    message.orientation = pose.rotation();
    message.rotation_rate_radps = Eigen::Vector3d(0.0, 0.0, yaw_rate_radps);
    message.acceleration_mps2 = Eigen::Vector3d(accel_mps2, speed_mps * yaw_rate_radps, 0.0);
    EXPECT_EQ(EncodePose(message), LegacyGroundTruth(StampToUtime(stamp_s), T, speed_mps,
                                                     yaw_rate_radps, accel_mps2))
        << T.angle_rad();
  }
}

TEST(LcmOutputConversionsTest, PoseRoundTrip) {
  PoseMessage in;
  in.stamp_s = 42.5;
  in.position_m = Eigen::Vector3d(1.0, -2.0, 0.5);
  in.velocity_mps = Eigen::Vector3d(0.3, 0.2, 0.1);
  in.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()));
  in.rotation_rate_radps = Eigen::Vector3d(0.01, 0.02, 0.03);
  in.acceleration_mps2 = Eigen::Vector3d(-1.0, 2.0, 9.81);
  const std::vector<uint8_t> bytes = EncodePose(in);
  PoseMessage out;
  std::string error;
  ASSERT_TRUE(DecodePose(bytes.data(), static_cast<int>(bytes.size()), &out, &error)) << error;
  EXPECT_DOUBLE_EQ(out.stamp_s, in.stamp_s);
  EXPECT_EQ(out.position_m, in.position_m);
  EXPECT_EQ(out.velocity_mps, in.velocity_mps);
  EXPECT_EQ(out.orientation.coeffs(), in.orientation.coeffs());
  EXPECT_EQ(out.rotation_rate_radps, in.rotation_rate_radps);
  EXPECT_EQ(out.acceleration_mps2, in.acceleration_mps2);
}

TEST(LcmOutputConversionsTest, DecodePoseRefusesTruncatedForeignAndNonFinite) {
  const std::vector<uint8_t> bytes = EncodePlanarPose(1.0, common::Rigid2d(1.0, 2.0, 0.5));
  PoseMessage out;
  std::string error;
  EXPECT_FALSE(DecodePose(bytes.data(), static_cast<int>(bytes.size()) - 1, &out, &error));
  EXPECT_FALSE(error.empty());

  fusemap_lcm::loop_closure_t other{};
  const std::vector<uint8_t> foreign = Bytes(other);
  EXPECT_FALSE(DecodePose(foreign.data(), static_cast<int>(foreign.size()), &out, &error));
  EXPECT_NE(error.find("pose_t"), std::string::npos) << error;

  PoseMessage nan;
  nan.position_m.x() = std::numeric_limits<double>::quiet_NaN();
  const std::vector<uint8_t> bad = EncodePose(nan);
  EXPECT_FALSE(DecodePose(bad.data(), static_cast<int>(bad.size()), &out, &error));
  EXPECT_NE(error.find("non-finite"), std::string::npos) << error;
}

TEST(LcmOutputConversionsTest, SubmapListBytesAndFields) {
  pose_graph::PoseGraphSnapshot snapshot;
  snapshot.solve_count = 17;
  snapshot.T_map_submaps = TestPoses();
  const std::vector<uint8_t> bytes = EncodeSubmapList(3.25, snapshot);

  fusemap_lcm::submap_list_t legacy;
  legacy.utime = StampToUtime(3.25);
  legacy.solve_count = 17;
  legacy.nsubmaps = static_cast<int32_t>(snapshot.T_map_submaps.size());
  for (const auto& T : snapshot.T_map_submaps) {
    legacy.x.push_back(T.translation().x());
    legacy.y.push_back(T.translation().y());
    legacy.theta.push_back(T.angle_rad());
  }
  EXPECT_EQ(bytes, Bytes(legacy));

  const auto msg = DecodeGenerated<fusemap_lcm::submap_list_t>(bytes);
  ASSERT_EQ(msg.nsubmaps, 5);
  EXPECT_EQ(msg.solve_count, 17);
  EXPECT_EQ(msg.x[1], 1.25);
  EXPECT_EQ(msg.y[2], 2.0);
  EXPECT_EQ(msg.theta[1], 1e-5);
}

TEST(LcmOutputConversionsTest, EmptySubmapList) {
  const auto msg =
      DecodeGenerated<fusemap_lcm::submap_list_t>(EncodeSubmapList(0.0, {}));
  EXPECT_EQ(msg.nsubmaps, 0);
  EXPECT_TRUE(msg.x.empty());
}

TEST(LcmOutputConversionsTest, LoopClosureFields) {
  pose_graph::PoseGraph2D::Stats stats;
  stats.loop_closures_found = 12;
  stats.optimizations = 4;
  const std::vector<uint8_t> bytes = EncodeLoopClosure(7.5, 2, stats, 311);

  fusemap_lcm::loop_closure_t legacy;
  legacy.utime = 7500000;
  legacy.new_loop_closures = 2;
  legacy.total_loop_closures = 12;
  legacy.optimizations = 4;
  legacy.latest_node = 311;
  legacy.source = "laser";
  legacy.decision = "";
  EXPECT_EQ(bytes, Bytes(legacy));

  const auto visual = DecodeGenerated<fusemap_lcm::loop_closure_t>(
      EncodeLoopClosure(7.5, 1, stats, 312, LoopNote{"visual", "visual_forced"}));
  EXPECT_EQ(visual.source, "visual");
  EXPECT_EQ(visual.decision, "visual_forced");
  EXPECT_EQ(visual.latest_node, 312);
}

TEST(LcmOutputConversionsTest, HealthFields) {
  HealthReport report;
  report.uptime_s = 61.5;
  report.channels.push_back({"LIDAR", 1500, 2, 3, 4, 99});
  report.channels.push_back({"RGBD", 600, 0, 1, 0, 0});
  report.latency.median_ms = 3.5;
  report.latency.p99_ms = 12.25;
  report.latency.max_ms = 40.0;
  report.rss_bytes = 123456789;
  report.nodes = 300;
  report.submaps = 7;
  report.constraints = 900;
  report.trimmed_nodes = 5;
  report.loop_closures = 3;
  report.optimizations = 2;
  report.checkpoint_failures = 1;
  report.time_resets = 6;
  report.visual = {40, 12, 9, 3, 2, 1, 5, 77};
  const std::vector<uint8_t> bytes = EncodeHealth(62.0, report);

  const auto msg = DecodeGenerated<fusemap_lcm::health_t>(bytes);
  EXPECT_EQ(msg.utime, 62000000);
  EXPECT_EQ(msg.uptime_s, 61.5);
  ASSERT_EQ(msg.nchannels, 2);
  EXPECT_EQ(msg.channel[1], "RGBD");
  EXPECT_EQ(msg.received[0], 1500);
  EXPECT_EQ(msg.dropped[0], 2);
  EXPECT_EQ(msg.malformed[1], 1);
  EXPECT_EQ(msg.queue_depth[0], 4);
  EXPECT_EQ(msg.latency_median_ms, 3.5);
  EXPECT_EQ(msg.latency_p99_ms, 12.25);
  EXPECT_EQ(msg.latency_max_ms, 40.0);
  EXPECT_EQ(msg.rss_bytes, 123456789);
  EXPECT_EQ(msg.nodes, 300);
  EXPECT_EQ(msg.submaps, 7);
  EXPECT_EQ(msg.constraints, 900);
  EXPECT_EQ(msg.loop_closures, 3);
  EXPECT_EQ(msg.optimizations, 2);
  EXPECT_EQ(msg.checkpoint_failures, 1);
  EXPECT_EQ(msg.time_resets, 6);
  EXPECT_EQ(msg.visual_keyframes, 40);
  EXPECT_EQ(msg.visual_candidates, 12);
  EXPECT_EQ(msg.visual_verified, 9);
  EXPECT_EQ(msg.visual_forced, 3);
  EXPECT_EQ(msg.visual_overridden, 2);
  EXPECT_EQ(msg.visual_rejected, 1);
  EXPECT_EQ(msg.visual_queue_depth, 5);
  EXPECT_EQ(msg.visual_dropped_frames, 77);
  // Field order on the wire is the .lcm file's, so re-encoding the decoded message gives the
  // same bytes.
  EXPECT_EQ(Bytes(msg), bytes);
}

TEST(LcmOutputConversionsTest, SubmapListRoundTrip) {
  pose_graph::PoseGraphSnapshot in;
  in.solve_count = 9;
  in.T_map_submaps = TestPoses();
  const std::vector<uint8_t> bytes = EncodeSubmapList(4.5, in);
  double stamp_s = 0.0;
  pose_graph::PoseGraphSnapshot out;
  std::string error;
  ASSERT_TRUE(DecodeSubmapList(bytes.data(), static_cast<int>(bytes.size()), &stamp_s, &out,
                               &error))
      << error;
  EXPECT_EQ(stamp_s, 4.5);
  EXPECT_EQ(out.solve_count, 9u);
  ASSERT_EQ(out.T_map_submaps.size(), in.T_map_submaps.size());
  for (size_t i = 0; i < in.T_map_submaps.size(); ++i) {
    EXPECT_EQ(out.T_map_submaps[i].translation(), in.T_map_submaps[i].translation());
    EXPECT_EQ(out.T_map_submaps[i].angle_rad(), in.T_map_submaps[i].angle_rad());
  }
}

HealthReport TwoChannelReport() {
  HealthReport report;
  report.uptime_s = 10.0;
  report.channels.push_back({"LIDAR", 250, 1, 2, 3, 0});
  report.channels.push_back({"ODOMETRY", 500, 0, 0, 1, 0});
  report.latency.median_ms = 2.0;
  report.rss_bytes = 1 << 20;
  report.nodes = 40;
  report.pending_searches = 17;
  report.time_resets = 1;
  report.visual.forced = 4;
  report.visual.dropped_frames = 9;
  return report;
}

TEST(LcmOutputConversionsTest, HealthRoundTrip) {
  const HealthReport in = TwoChannelReport();
  const std::vector<uint8_t> bytes = EncodeHealth(11.0, in);
  double stamp_s = 0.0;
  HealthReport out;
  std::string error;
  ASSERT_TRUE(DecodeHealth(bytes.data(), static_cast<int>(bytes.size()), &stamp_s, &out, &error))
      << error;
  EXPECT_EQ(stamp_s, 11.0);
  ASSERT_EQ(out.channels.size(), 2u);
  EXPECT_EQ(out.channels[1].name, "ODOMETRY");
  EXPECT_EQ(out.channels[0].received, 250);
  EXPECT_EQ(out.channels[0].malformed, 2);
  EXPECT_EQ(out.channels[0].queue_depth, 3);
  EXPECT_EQ(out.latency.median_ms, 2.0);
  EXPECT_EQ(out.rss_bytes, 1 << 20);
  EXPECT_EQ(out.nodes, 40);
  EXPECT_EQ(out.pending_searches, 17);
  EXPECT_EQ(out.time_resets, 1);
  EXPECT_EQ(out.visual.forced, 4);
  EXPECT_EQ(out.visual.dropped_frames, 9);
  EXPECT_EQ(EncodeHealth(stamp_s, out), bytes);
}

// Every prefix and one extra byte are refused with a reason; none crashes the decoder.
template <class Decode>
void ExpectEveryTruncationRefused(const std::vector<uint8_t>& bytes, Decode decode) {
  for (size_t n = 0; n < bytes.size(); ++n) {
    std::string error;
    EXPECT_FALSE(decode(std::vector<uint8_t>(bytes.begin(), bytes.begin() + n), &error)) << n;
    EXPECT_FALSE(error.empty()) << n;
  }
  std::vector<uint8_t> longer = bytes;
  longer.push_back(0);
  std::string error;
  EXPECT_FALSE(decode(longer, &error));
  EXPECT_NE(error.find("trailing"), std::string::npos) << error;
}

TEST(LcmOutputConversionsTest, SubmapListAndHealthRefuseTruncatedAndLongerMessages) {
  pose_graph::PoseGraphSnapshot snapshot;
  snapshot.T_map_submaps = TestPoses();
  ExpectEveryTruncationRefused(
      EncodeSubmapList(1.0, snapshot), [](const std::vector<uint8_t>& b, std::string* error) {
        double stamp_s;
        pose_graph::PoseGraphSnapshot out;
        return DecodeSubmapList(b.data(), static_cast<int>(b.size()), &stamp_s, &out, error);
      });
  ExpectEveryTruncationRefused(
      EncodeHealth(1.0, TwoChannelReport()), [](const std::vector<uint8_t>& b, std::string* error) {
        double stamp_s;
        HealthReport out;
        return DecodeHealth(b.data(), static_cast<int>(b.size()), &stamp_s, &out, error);
      });
}

TEST(LcmOutputConversionsTest, AbsurdCountsAreRefusedBeforeDecoding) {
  fusemap_lcm::health_t health{};
  health.nchannels = -1;  // The generated encoder writes the count as given.
  std::vector<uint8_t> bytes = Bytes(health);
  double stamp_s;
  HealthReport report;
  std::string error;
  EXPECT_FALSE(DecodeHealth(bytes.data(), static_cast<int>(bytes.size()), &stamp_s, &report,
                            &error));
  EXPECT_NE(error.find("absurd count -1"), std::string::npos) << error;

  pose_graph::PoseGraphSnapshot snapshot;
  snapshot.T_map_submaps = TestPoses();
  bytes = EncodeSubmapList(1.0, snapshot);
  bytes[8 + 16] = 0x7f;  // nsubmaps' most significant byte.
  EXPECT_FALSE(DecodeSubmapList(bytes.data(), static_cast<int>(bytes.size()), &stamp_s,
                                &snapshot, &error));
  EXPECT_NE(error.find("absurd count"), std::string::npos) << error;
}

TEST(LcmOutputConversionsTest, CloudRegionFields) {
  CloudRegionUpdate update;
  update.stamp_s = 9.0;
  update.submap_id = 4;
  update.T_map_submap = common::Rigid3d(Eigen::Vector3d(1.0, 2.0, 0.5),
                                        Eigen::Quaterniond(Eigen::AngleAxisd(
                                            0.3, Eigen::Vector3d::UnitZ())));
  update.total_points = 1000;
  update.points_submap.reset(new cloud::ColorCloud);
  cloud::ColorPoint p;
  p.x = 0.5f;
  p.y = -1.0f;
  p.z = 2.0f;
  p.r = 10;
  p.g = 200;
  p.b = 255;
  update.points_submap->push_back(p);
  p.x = 3.0f;
  p.r = 0;
  update.points_submap->push_back(p);

  const auto msg = DecodeGenerated<fusemap_lcm::cloud_region_t>(EncodeCloudRegion(update));
  EXPECT_EQ(msg.utime, 9000000);
  EXPECT_EQ(msg.submap_id, 4);
  EXPECT_EQ(msg.total_points, 1000);
  EXPECT_EQ(msg.T_map_submap.translation[2], 0.5);
  EXPECT_EQ(msg.T_map_submap.rotation[0], update.T_map_submap.rotation().w());
  EXPECT_EQ(msg.T_map_submap.rotation[3], update.T_map_submap.rotation().z());
  ASSERT_EQ(msg.npoints, 2);
  EXPECT_EQ(msg.xyz[0][1], -1.0f);
  EXPECT_EQ(msg.xyz[1][0], 3.0f);
  EXPECT_EQ(msg.rgb[0][1], 200);
  EXPECT_EQ(msg.rgb[0][2], 255);
  EXPECT_EQ(msg.rgb[1][0], 0);
}

}  // namespace
}  // namespace io
}  // namespace fusemap
