#ifndef FUSEMAP_TEST_TESTING_ROOM_MAP_BUILDER_OPTIONS_H_
#define FUSEMAP_TEST_TESTING_ROOM_MAP_BUILDER_OPTIONS_H_

#include "fusemap/common/math.h"
#include "fusemap/pose_graph/map_builder_2d.h"

namespace fusemap {
namespace test_world {

// SLAM options for runs around the synthetic room (synthetic_room.h): small submaps, frequent
// optimisation and every node searched, so a short run already closes loops. Local SLAM is
// deliberately weaker (Ceres refinement only, no correlative search) so that it drifts by
// decimetres over the loop and loop closure has something to remove.
inline pose_graph::MapBuilderOptions2D RoomMapBuilderOptions() {
  pose_graph::MapBuilderOptions2D options;
  options.local_slam.use_imu = false;
  options.local_slam.submaps.num_range_data = 10;
  options.local_slam.use_online_correlative_scan_matching = false;
  // Without the correlative search first, Ceres alone with never-observed cells read as 0.5
  // is pushed outward at the edge of the observed area and drifts over a metre on this loop;
  // read as the grid stores them, the drift stays at the decimetres these tests are set for.
  options.local_slam.ceres_scan_matcher.unknown_probability = mapping::kMinProbability;
  // Cartographer's weight, not the default 10, which follows the map so closely here that the
  // loop's end is off by only ~5 cm.
  options.local_slam.ceres_scan_matcher.occupied_space_weight = 1.0;
  options.global_slam.optimize_every_n_nodes = 15;
  auto& constraints = options.global_slam.constraint_builder;
  constraints.sampling_ratio = 1.0;
  constraints.max_constraint_distance_m = 3.0;
  constraints.fast_correlative_scan_matcher.linear_search_window_m = 1.0;
  constraints.fast_correlative_scan_matcher.angular_search_window_rad = common::DegToRad(15.0);
  // Cartographer's weights, not the default 100x: every node is searched here, so closures are
  // many and each may pull softly (with 100x the trimmed run's end drifted 0.14 m).
  constraints.loop_closure_translation_weight = 1.1e4;
  constraints.loop_closure_rotation_weight = 1e5;
  return options;
}

}  // namespace test_world
}  // namespace fusemap

#endif  // FUSEMAP_TEST_TESTING_ROOM_MAP_BUILDER_OPTIONS_H_
