#ifndef FUSEMAP_TEST_TESTING_ROOM_SLAM_CONFIG_H_
#define FUSEMAP_TEST_TESTING_ROOM_SLAM_CONFIG_H_

#include "fusemap/io/slam_config.h"
#include "testing/room_map_builder_options.h"

namespace fusemap {
namespace test_world {

// The room's SLAM options (room_map_builder_options.h) as a whole SLAM profile.
inline io::SlamConfig RoomSlamConfig() {
  io::SlamConfig config;
  config.map_builder = RoomMapBuilderOptions();
  return config;
}

}  // namespace test_world
}  // namespace fusemap

#endif  // FUSEMAP_TEST_TESTING_ROOM_SLAM_CONFIG_H_
