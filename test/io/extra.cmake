# libbot2 reference types (bot_core), generated only for io_lcm_fingerprint_test.
set(io_botcore_dir ${CMAKE_CURRENT_BINARY_DIR}/io_bot_core)
set(io_botcore_lcm ${CMAKE_CURRENT_SOURCE_DIR}/io/data/bot_core_planar_lidar_t.lcm
                   ${CMAKE_CURRENT_SOURCE_DIR}/io/data/bot_core_pose_t.lcm)
add_custom_command(
  OUTPUT ${io_botcore_dir}/bot_core/planar_lidar_t.hpp ${io_botcore_dir}/bot_core/pose_t.hpp
  COMMAND ${LCM_GEN} --cpp --cpp-hpath ${io_botcore_dir} ${io_botcore_lcm}
  DEPENDS ${io_botcore_lcm}
  COMMENT "lcm-gen --cpp (bot_core reference types)"
  VERBATIM)
add_custom_target(io_botcore_lcmtypes_gen
  DEPENDS ${io_botcore_dir}/bot_core/planar_lidar_t.hpp ${io_botcore_dir}/bot_core/pose_t.hpp)
if(TARGET io_lcm_fingerprint_test)
  add_dependencies(io_lcm_fingerprint_test io_botcore_lcmtypes_gen)
  target_include_directories(io_lcm_fingerprint_test PRIVATE ${io_botcore_dir})
endif()
