#include "fusemap/daemon/intake.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "fusemap/io/lcm_conversions.h"
#include "fusemap/io/rgbd_conversions.h"
#include "fusemap_lcm/rgbd_frame_t.hpp"

namespace fusemap {
namespace daemon {
namespace {

constexpr double kNowS = 1700000100.0;

sensor::LaserScan Scan(double stamp_s, int beams = 100) {
  sensor::LaserScan scan;
  scan.stamp_s = stamp_s;
  scan.angle_min_rad = -1.f;
  scan.angle_increment_rad = 0.02f;
  scan.range_min_m = 0.1f;
  scan.range_max_m = 10.f;
  scan.ranges_m.assign(beams, 3.f);
  return scan;
}

class IntakeTest : public ::testing::Test {
 protected:
  IntakeTest() : log_(0.0, [] { return 0.0; }, [this](const std::string& l) { lines_.push_back(l); }) {}

  std::unique_ptr<Intake> Make(OverflowPolicy policy, int queue_size = 100) {
    DaemonOptions options;
    options.sensor_queue_size = queue_size;
    return std::make_unique<Intake>(io::SlamConfig(), options, policy, &log_, [] { return kNowS; });
  }
  static bool Send(Intake& intake, const std::string& channel, const std::vector<uint8_t>& bytes) {
    return intake.OnMessage(channel, bytes.data(), static_cast<int>(bytes.size()));
  }

  std::vector<std::string> lines_;
  RateLimitedLog log_;
};

TEST_F(IntakeTest, ValidMessagesQueuedInArrivalOrder) {
  auto intake = Make(OverflowPolicy::kDropOldest);
  EXPECT_TRUE(Send(*intake, "ODOMETRY", io::EncodeOdometry({kNowS - 2.0, common::Rigid2d()})));
  EXPECT_TRUE(Send(*intake, "LIDAR", io::EncodeLaserScan(Scan(kNowS - 1.9))));
  sensor::ImuData imu;
  imu.stamp_s = kNowS - 1.8;
  EXPECT_TRUE(Send(*intake, "IMU", io::EncodeImu(imu)));
  EXPECT_FALSE(Send(*intake, "OTHER", io::EncodeImu(imu)));
  ASSERT_EQ(intake->sensor_queue().size(), 3u);
  EXPECT_TRUE(std::holds_alternative<sensor::OdometryData>(intake->sensor_queue().Pop()->data));
  auto scan = intake->sensor_queue().Pop();
  EXPECT_EQ(scan->channel, kLidarChannel);
  EXPECT_EQ(std::get<sensor::LaserScan>(scan->data).ranges_m.size(), 100u);
  EXPECT_TRUE(std::holds_alternative<sensor::ImuData>(intake->sensor_queue().Pop()->data));
  EXPECT_EQ(intake->counters(kLidarChannel).received, 1);
  EXPECT_TRUE(lines_.empty());
}

TEST_F(IntakeTest, MalformedMessagesCountedPerChannelAndLogged) {
  auto intake = Make(OverflowPolicy::kDropOldest);
  std::vector<uint8_t> scan = io::EncodeLaserScan(Scan(kNowS - 1.0));
  std::vector<uint8_t> truncated(scan.begin(), scan.begin() + scan.size() / 2);
  EXPECT_FALSE(Send(*intake, "LIDAR", truncated));
  std::vector<uint8_t> wrong_fingerprint = scan;
  wrong_fingerprint[0] ^= 0xff;
  EXPECT_FALSE(Send(*intake, "LIDAR", wrong_fingerprint));
  sensor::LaserScan nan_scan = Scan(kNowS - 1.0);
  for (size_t i = 0; i < 60; ++i) nan_scan.ranges_m[i] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(Send(*intake, "LIDAR", io::EncodeLaserScan(nan_scan)));
  EXPECT_FALSE(Send(*intake, "LIDAR", io::EncodeLaserScan(Scan(kNowS + 60.0))));  // future
  EXPECT_TRUE(Send(*intake, "LIDAR", scan));
  EXPECT_FALSE(Send(*intake, "LIDAR", io::EncodeLaserScan(Scan(kNowS - 2.0))));  // backwards
  EXPECT_FALSE(Send(*intake, "ODOMETRY", std::vector<uint8_t>(3, 0)));
  std::vector<uint8_t> huge(DaemonOptions().max_message_bytes + 1, 0);
  EXPECT_FALSE(Send(*intake, "IMU", huge));

  EXPECT_EQ(intake->counters(kLidarChannel).received, 6);
  EXPECT_EQ(intake->counters(kLidarChannel).malformed, 5);
  EXPECT_EQ(intake->counters(kOdometryChannel).malformed, 1);
  EXPECT_EQ(intake->counters(kImuChannel).malformed, 1);
  EXPECT_EQ(intake->sensor_queue().size(), 1u);
  ASSERT_EQ(lines_.size(), 7u);  // interval 0: every report is written
  EXPECT_NE(lines_[3].find("future"), std::string::npos) << lines_[3];
  EXPECT_NE(lines_[4].find("backwards"), std::string::npos) << lines_[4];
}

TEST_F(IntakeTest, OverflowDropsOldestAndCountsItsChannel) {
  auto intake = Make(OverflowPolicy::kDropOldest, 2);
  EXPECT_TRUE(Send(*intake, "ODOMETRY", io::EncodeOdometry({kNowS - 3.0, common::Rigid2d()})));
  for (int i = 0; i < 3; ++i) {
    EXPECT_TRUE(Send(*intake, "LIDAR", io::EncodeLaserScan(Scan(kNowS - 2.0 + 0.1 * i))));
  }
  EXPECT_EQ(intake->counters(kOdometryChannel).dropped, 1);
  EXPECT_EQ(intake->counters(kLidarChannel).dropped, 1);
  const auto rows = intake->ChannelHealth();
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0].name, "LIDAR");
  EXPECT_EQ(rows[0].queue_depth, 2);
  EXPECT_DOUBLE_EQ(
      std::get<sensor::LaserScan>(intake->sensor_queue().Pop()->data).stamp_s, kNowS - 1.9);
}

TEST_F(IntakeTest, RgbdIgnoredWithoutConsumerAndCloseRefuses) {
  auto intake = Make(OverflowPolicy::kBlock);
  EXPECT_FALSE(Send(*intake, "RGBD", std::vector<uint8_t>(10, 1)));
  EXPECT_EQ(intake->counters(kRgbdChannel).received, 1);
  EXPECT_EQ(intake->counters(kRgbdChannel).malformed, 0);
  intake->set_decode_rgbd(true);
  EXPECT_FALSE(Send(*intake, "RGBD", std::vector<uint8_t>(10, 1)));
  EXPECT_EQ(intake->counters(kRgbdChannel).malformed, 1);
  intake->Close();
  EXPECT_FALSE(Send(*intake, "LIDAR", io::EncodeLaserScan(Scan(kNowS - 1.0))));
  EXPECT_TRUE(intake->sensor_queue().closed_and_drained());
}

// A looping log player: after t0+10 s the stamps start again at t0. The jump (> 5 s) on the laser
// is a time reset: everything after it is shifted onto one monotonic clock, 1 s after the newest
// stamp; odometry of the new loop that arrives before the reset scan is held, and released on
// the new clock once the laser has reset (it was dropped as "backwards" before).
TEST_F(IntakeTest, LaserJumpBackIsATimeResetAndLaterStampsAreRebased) {
  auto intake = Make(OverflowPolicy::kDropOldest);
  const double t0 = kNowS - 100.0;
  EXPECT_TRUE(Send(*intake, "ODOMETRY", io::EncodeOdometry({t0 + 9.9, common::Rigid2d()})));
  EXPECT_TRUE(Send(*intake, "LIDAR", io::EncodeLaserScan(Scan(t0 + 10.0))));
  EXPECT_FALSE(Send(*intake, "ODOMETRY", io::EncodeOdometry({t0, common::Rigid2d()})));
  EXPECT_FALSE(Send(*intake, "LIDAR", io::EncodeLaserScan(Scan(t0 + 6.0))));  // 4 s: backwards
  EXPECT_EQ(intake->time_resets(), 0);
  EXPECT_TRUE(Send(*intake, "LIDAR", io::EncodeLaserScan(Scan(t0 + 0.1))));  // 9.9 s: reset
  EXPECT_EQ(intake->time_resets(), 1);
  EXPECT_TRUE(Send(*intake, "ODOMETRY", io::EncodeOdometry({t0 + 0.15, common::Rigid2d()})));
  EXPECT_TRUE(Send(*intake, "LIDAR", io::EncodeLaserScan(Scan(t0 + 0.2))));
  // A second loop: a second reset, on top of the first offset.
  EXPECT_TRUE(Send(*intake, "LIDAR", io::EncodeLaserScan(Scan(t0 + 10.0))));
  EXPECT_TRUE(Send(*intake, "LIDAR", io::EncodeLaserScan(Scan(t0 + 0.1))));
  EXPECT_EQ(intake->time_resets(), 2);

  std::vector<double> stamps;
  std::vector<bool> after_reset;
  while (intake->sensor_queue().size() > 0) {
    auto m = intake->sensor_queue().Pop();
    stamps.push_back(m->channel == kLidarChannel
                         ? std::get<sensor::LaserScan>(m->data).stamp_s
                         : std::get<sensor::OdometryData>(m->data).stamp_s);
    after_reset.push_back(m->after_time_reset);
  }
  // The first message on each new time base tells the SLAM thread, in order with the data.
  EXPECT_EQ(after_reset,
            std::vector<bool>({false, false, true, false, false, false, false, true}));
  const double gap = Intake::kTimeResetGapS;
  const std::vector<double> expected = {t0 + 9.9,         t0 + 10.0,       t0 + 10.0 + gap,
                                        t0 + 9.9 + gap,   t0 + 10.05 + gap, t0 + 10.1 + gap,
                                        t0 + 19.9 + gap,  t0 + 19.9 + 2 * gap};
  ASSERT_EQ(stamps.size(), expected.size());
  for (size_t i = 0; i < stamps.size(); ++i) EXPECT_NEAR(stamps[i], expected[i], 1e-6) << i;
  EXPECT_EQ(intake->counters(kLidarChannel).malformed, 1);
  EXPECT_EQ(intake->counters(kOdometryChannel).malformed, 0);
}

// Issue 18 item 10: after --resume a replay from the log's start is skipped up to the
// checkpoint (counted as skipped), not mapped again through a time reset.
TEST_F(IntakeTest, ResumePointSkipsWhatTheCheckpointHolds) {
  auto intake = Make(OverflowPolicy::kDropOldest);
  const double t0 = kNowS - 1000.0;
  intake->SetResumePoint(kLidarChannel, t0 + 300.0);
  intake->SetResumePoint(kOdometryChannel, t0 + 300.01);
  for (int i = 0; i <= 3000; ++i) {
    Send(*intake, "ODOMETRY", io::EncodeOdometry({t0 + 0.1 * i + 0.01, common::Rigid2d()}));
    Send(*intake, "LIDAR", io::EncodeLaserScan(Scan(t0 + 0.1 * i)));
  }
  EXPECT_EQ(intake->time_resets(), 0);
  EXPECT_EQ(intake->counters(kLidarChannel).skipped, 3001);
  EXPECT_EQ(intake->counters(kOdometryChannel).skipped, 3001);
  EXPECT_EQ(intake->counters(kLidarChannel).malformed, 0);
  EXPECT_EQ(intake->sensor_queue().size(), 0u);
  EXPECT_TRUE(Send(*intake, "LIDAR", io::EncodeLaserScan(Scan(t0 + 300.1))));
  EXPECT_TRUE(Send(*intake, "ODOMETRY", io::EncodeOdometry({t0 + 300.11, common::Rigid2d()})));
  // Past the checkpoint, a loop of the log is a time reset again.
  EXPECT_TRUE(Send(*intake, "LIDAR", io::EncodeLaserScan(Scan(t0))));
  EXPECT_EQ(intake->time_resets(), 1);
  HealthReport report;
  report.channels = intake->ChannelHealth();
  EXPECT_NE(FormatHealth(report).find("resume_skipped=6002"), std::string::npos);
}

TEST_F(IntakeTest, TimeResetCanBeDisabled) {
  DaemonOptions options;
  options.time_reset_threshold_s = 0.0;
  Intake intake(io::SlamConfig(), options, OverflowPolicy::kDropOldest, &log_,
                [] { return kNowS; });
  EXPECT_TRUE(Send(intake, "LIDAR", io::EncodeLaserScan(Scan(kNowS - 9.0))));
  EXPECT_FALSE(Send(intake, "LIDAR", io::EncodeLaserScan(Scan(kNowS - 60.0))));
  EXPECT_EQ(intake.time_resets(), 0);
  EXPECT_EQ(intake.counters(kLidarChannel).malformed, 1);
}

// Issue 18 item 6: one odometry stamp 11.6 days ahead (still before the wall clock) made the
// 990 valid messages after it "go backwards". Now it costs itself only, and the counters blame
// it alone; IMU the same.
TEST_F(IntakeTest, OneStampFarAheadCostsOnlyThatMessage) {
  DaemonOptions options;
  options.sensor_queue_size = 10000;
  Intake intake(io::SlamConfig(), options, OverflowPolicy::kBlock, &log_,
                [] { return kNowS + 30 * 86400.0; });
  const double t0 = kNowS - 100.0;
  for (int i = 0; i < 1000; ++i) {
    const double ahead_s = i == 10 ? 11.6 * 86400.0 : 0.0;
    Send(intake, "ODOMETRY", io::EncodeOdometry({t0 + 0.02 * i + ahead_s, common::Rigid2d()}));
    sensor::ImuData imu;
    for (int k = 0; k < 4; ++k) {
      imu.stamp_s = t0 + 0.02 * i + 0.005 * k + (i == 20 && k == 1 ? 11.6 * 86400.0 : 0.0);
      Send(intake, "IMU", io::EncodeImu(imu));
    }
  }
  EXPECT_EQ(intake.counters(kOdometryChannel).malformed, 1);
  EXPECT_EQ(intake.counters(kImuChannel).malformed, 1);
  EXPECT_EQ(intake.sensor_queue().size(), 999u + 3999u);
  int odometry = 0;
  double last_s = 0.0;
  while (intake.sensor_queue().size() > 0) {
    auto m = intake.sensor_queue().Pop();
    if (m->channel != kOdometryChannel) continue;
    const double stamp_s = std::get<sensor::OdometryData>(m->data).stamp_s;
    EXPECT_LT(stamp_s, t0 + 21.0);
    EXPECT_GT(stamp_s, last_s);
    last_s = stamp_s;
    ++odometry;
  }
  EXPECT_EQ(odometry, 999);
  bool blamed = false;
  for (const auto& line : lines_) blamed |= line.find("outlier") != std::string::npos;
  EXPECT_TRUE(blamed);
}

// Issue 18 item 7: utime -2^62 on the laser was taken as a time reset and shifted the rest of
// the run by 4.6e12 s.
TEST_F(IntakeTest, AbsurdLaserStampIsMalformedNotATimeReset) {
  auto intake = Make(OverflowPolicy::kDropOldest);
  const double t0 = kNowS - 100.0;
  EXPECT_TRUE(Send(*intake, "LIDAR", io::EncodeLaserScan(Scan(t0))));
  EXPECT_FALSE(Send(*intake, "LIDAR", io::EncodeLaserScan(Scan(-4611686018427.387904))));
  EXPECT_EQ(intake->time_resets(), 0);
  EXPECT_EQ(intake->counters(kLidarChannel).malformed, 1);
  EXPECT_TRUE(Send(*intake, "LIDAR", io::EncodeLaserScan(Scan(t0 + 0.1))));
  intake->sensor_queue().Pop();
  EXPECT_NEAR(std::get<sensor::LaserScan>(intake->sensor_queue().Pop()->data).stamp_s, t0 + 0.1,
              1e-6);
}

// Issue 18 item 8: odometry x = 1e300 was accepted and reached trajectory.tum.
TEST_F(IntakeTest, AbsurdOdometryAndImuValuesAreMalformed) {
  auto intake = Make(OverflowPolicy::kDropOldest);
  EXPECT_FALSE(Send(*intake, "ODOMETRY",
                    io::EncodeOdometry({kNowS - 2.0, common::Rigid2d(1e300, 0.0, 0.0)})));
  EXPECT_FALSE(Send(*intake, "ODOMETRY",
                    io::EncodeOdometry({kNowS - 2.0, common::Rigid2d(0.0, -2e7, 0.0)})));
  sensor::ImuData imu;
  imu.stamp_s = kNowS - 2.0;
  imu.angular_velocity_radps.z() = 1e200;
  EXPECT_FALSE(Send(*intake, "IMU", io::EncodeImu(imu)));
  EXPECT_EQ(intake->counters(kOdometryChannel).malformed, 2);
  EXPECT_EQ(intake->counters(kImuChannel).malformed, 1);
  EXPECT_TRUE(Send(*intake, "ODOMETRY",
                   io::EncodeOdometry({kNowS - 2.0, common::Rigid2d(1e4, -1e4, 100.0)})));
}

sensor::RgbdFrame SmallFrame(double stamp_s) {
  sensor::RgbdFrame frame;
  frame.stamp_s = stamp_s;
  frame.frame = "camera";
  frame.color_intrinsics = sensor::PinholeIntrinsics{32, 24, 30.0, 30.0, 16.0, 12.0};
  frame.depth_intrinsics = frame.color_intrinsics;
  frame.color_rgb.assign(32 * 24 * 3, 100);
  frame.depth_mm.assign(32 * 24, 1500);
  return frame;
}

// Re-encodes a frame's message after `edit` (a hostile sender).
template <typename Edit>
std::vector<uint8_t> EditedFrame(double stamp_s, Edit edit) {
  std::vector<uint8_t> bytes;
  std::string error;
  EXPECT_TRUE(io::EncodeRgbdFrame(SmallFrame(stamp_s), io::RgbdEncodeOptions(), &bytes, &error)) << error;
  fusemap_lcm::rgbd_frame_t msg;
  msg.decode(bytes.data(), 0, static_cast<int>(bytes.size()));
  edit(&msg);
  msg.color_size = static_cast<int32_t>(msg.color_data.size());
  msg.depth_size = static_cast<int32_t>(msg.depth_data.size());
  bytes.resize(msg.getEncodedSize());
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

// Issue 18, items 1 and 2: an empty image aborted the daemon on the handler thread; images are
// now only checked there (size from their headers) and decoded by whoever pops the queue, and
// a body that does not decode is counted as malformed then.
TEST_F(IntakeTest, RgbdImagesAreCheckedOnTheHandlerAndDecodedByTheConsumer) {
  auto intake = Make(OverflowPolicy::kBlock);
  intake->set_decode_rgbd(true);
  EXPECT_FALSE(Send(*intake, "RGBD", EditedFrame(kNowS - 3.0, [](auto* m) { m->color_data.clear(); })));
  EXPECT_FALSE(Send(*intake, "RGBD", EditedFrame(kNowS - 2.9, [](auto* m) { m->depth_data.clear(); })));
  EXPECT_EQ(intake->counters(kRgbdChannel).malformed, 2);
  // A valid frame is queued with its images still compressed.
  EXPECT_TRUE(Send(*intake, "RGBD", EditedFrame(kNowS - 2.0, [](auto*) {})));
  // A frame whose JPEG header is fine but whose body is garbage passes the handler.
  EXPECT_TRUE(Send(*intake, "RGBD", EditedFrame(kNowS - 1.0, [](auto* m) {
    for (size_t i = m->depth_data.size() / 2; i < m->depth_data.size(); ++i) m->depth_data[i] ^= 0x5a;
  })));
  EXPECT_EQ(intake->counters(kRgbdChannel).malformed, 2);
  auto good = intake->rgbd_queue().Pop();
  ASSERT_TRUE(good.has_value());
  EXPECT_TRUE(good->frame.color_rgb.empty());
  EXPECT_FALSE(good->images.color_data.empty());
  ASSERT_TRUE(intake->DecodeImages(&*good));
  EXPECT_EQ(good->frame.depth_mm, SmallFrame(0.0).depth_mm);
  EXPECT_EQ(good->frame.color_rgb.size(), 32u * 24u * 3u);
  auto bad = intake->rgbd_queue().Pop();
  ASSERT_TRUE(bad.has_value());
  EXPECT_FALSE(intake->DecodeImages(&*bad));
  EXPECT_EQ(intake->counters(kRgbdChannel).malformed, 3);
}

// The configured camera bound: larger images are refused before anything is decoded.
TEST_F(IntakeTest, RgbdImagesOverTheCameraBoundAreRejected) {
  DaemonOptions options;
  options.max_image_pixels = 32 * 23;
  Intake intake(io::SlamConfig(), options, OverflowPolicy::kBlock, &log_, [] { return kNowS; });
  intake.set_decode_rgbd(true);
  EXPECT_FALSE(Send(intake, "RGBD", EditedFrame(kNowS - 1.0, [](auto*) {})));
  EXPECT_EQ(intake.counters(kRgbdChannel).malformed, 1);
  EXPECT_NE(lines_.back().find("more than daemon.max_image_pixels 736"), std::string::npos) << lines_.back();
}

}  // namespace
}  // namespace daemon
}  // namespace fusemap
