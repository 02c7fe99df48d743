#ifndef FUSEMAP_TEST_TESTING_ROOM_SLAM_CONFIG_H_
#define FUSEMAP_TEST_TESTING_ROOM_SLAM_CONFIG_H_

#include "fusemap/common/math.h"
#include "fusemap/io/slam_config.h"

namespace fusemap {
namespace test_world {

// SLAM options for runs around the synthetic room (synthetic_room.h): small submaps, frequent
// optimisation and every node searched, so a short test log already closes loops.
inline io::SlamConfig RoomSlamConfig() {
  io::SlamConfig config;
  auto& options = config.map_builder;
  options.local_slam.use_imu = false;
  options.local_slam.submaps.num_range_data = 10;
  options.local_slam.use_online_correlative_scan_matching = false;
  options.global_slam.optimize_every_n_nodes = 15;
  auto& constraints = options.global_slam.constraint_builder;
  constraints.sampling_ratio = 1.0;
  constraints.max_constraint_distance_m = 3.0;
  constraints.fast_correlative_scan_matcher.linear_search_window_m = 1.0;
  constraints.fast_correlative_scan_matcher.angular_search_window_rad = common::DegToRad(15.0);
  return config;
}

}  // namespace test_world
}  // namespace fusemap

#endif  // FUSEMAP_TEST_TESTING_ROOM_SLAM_CONFIG_H_
