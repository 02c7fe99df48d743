# fusemapd end to end in a private network namespace (no traffic can leave it): simulate a log,
# replay it with lcm-logplayer over loopback multicast, record the daemon's outputs with
# lcm-logger, check them with daemon_log_check, stop the daemon with SIGTERM, check its files.
add_executable(daemon_log_check ${CMAKE_CURRENT_SOURCE_DIR}/daemon/log_check.cc)
target_link_libraries(daemon_log_check PRIVATE fusemap_daemon)
target_compile_options(daemon_log_check PRIVATE -Wall -Wextra)
if(TARGET fusemapd AND TARGET fusemap_sim_tool)
  add_test(NAME daemon_netns_integration
           COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/daemon/netns_integration.sh
                   $<TARGET_FILE:fusemapd> $<TARGET_FILE:fusemap_sim_tool>
                   $<TARGET_FILE:daemon_log_check> ${PROJECT_SOURCE_DIR})
  set_tests_properties(daemon_netns_integration PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 240)
endif()
# kill -9 mid-run, --resume, whole-run outputs; truncated checkpoint falls back to .prev.
if(TARGET fusemapd AND TARGET fusemap_sim_tool)
  add_test(NAME daemon_kill_resume
           COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/daemon/kill_resume.sh
                   $<TARGET_FILE:fusemapd> $<TARGET_FILE:fusemap_sim_tool> ${PROJECT_SOURCE_DIR})
  set_tests_properties(daemon_kill_resume PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 400)
endif()
# The far-odometry replay runs fusemap_offline itself.
if(TARGET daemon_far_odometry_replay_test AND TARGET fusemap_offline)
  add_dependencies(daemon_far_odometry_replay_test fusemap_offline)
  target_compile_definitions(daemon_far_odometry_replay_test PRIVATE
    FUSEMAP_OFFLINE_BINARY="$<TARGET_FILE:fusemap_offline>")
endif()
