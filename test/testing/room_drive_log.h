#ifndef FUSEMAP_TEST_TESTING_ROOM_DRIVE_LOG_H_
#define FUSEMAP_TEST_TESTING_ROOM_DRIVE_LOG_H_

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "fusemap/common/math.h"
#include "fusemap/io/lcm_conversions.h"
#include "testing/synthetic_room.h"

namespace fusemap {
namespace test_world {

struct EncodedMessage {
  std::string channel;
  double stamp_s;
  std::vector<uint8_t> data;
};

// 1.1 turns around the synthetic room's island, encoded as the robot would publish it: a scan
// on LIDAR per step of step_m every 0.1 s, and drifting odometry on ODOMETRY twice per step
// (2 % scale error, 0.3 deg yaw bias per step), so loop closure has drift to remove.
inline std::vector<EncodedMessage> RoomDriveMessages(double step_m, double start_s,
                                                     unsigned seed) {
  const auto walls = Room();
  std::mt19937 rng(seed);
  std::vector<EncodedMessage> log;
  const int num_scans = static_cast<int>(1.1 * 2.0 * common::kPi * kArcRadiusM / step_m);
  common::Rigid2d odom = ArcPose(0, step_m);
  for (int i = 0; i < num_scans; ++i) {
    const double stamp_s = start_s + 0.1 * i;
    if (i > 0) {
      const common::Rigid2d delta = ArcPose(i - 1, step_m).inverse() * ArcPose(i, step_m);
      const common::Rigid2d half(0.51 * delta.translation(),
                                 0.5 * delta.angle_rad() + common::DegToRad(0.15));
      odom = odom * half;
      log.push_back({"ODOMETRY", stamp_s - 0.05, io::EncodeOdometry({stamp_s - 0.05, odom})});
      odom = odom * half;
    }
    log.push_back({"ODOMETRY", stamp_s, io::EncodeOdometry({stamp_s, odom})});
    log.push_back({"LIDAR", stamp_s,
                   io::EncodeLaserScan(SimulateScan(walls, ArcPose(i, step_m), stamp_s, 0.02, &rng))});
  }
  return log;
}

}  // namespace test_world
}  // namespace fusemap

#endif  // FUSEMAP_TEST_TESTING_ROOM_DRIVE_LOG_H_
