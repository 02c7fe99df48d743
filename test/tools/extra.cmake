# Exit codes of every binary under tools/ (README "Exit codes"); the ones not built are left out.
set(tools_exit_code_args)
foreach(tool fusemap_carmen2lcm fusemap_offline fusemapd fusemap_cloudeval fusemap_bench_cloud
             fusemap_g2o fusemap_tagscore fusemap_vloop fusemap_bench_vloop fusemap_bench_images)
  if(TARGET ${tool})
    list(APPEND tools_exit_code_args ${tool}=$<TARGET_FILE:${tool}>)
  endif()
endforeach()
if(TARGET fusemap_eval_tool)
  list(APPEND tools_exit_code_args fusemap_eval=$<TARGET_FILE:fusemap_eval_tool>)
endif()
if(TARGET fusemap_sim_tool)
  list(APPEND tools_exit_code_args fusemap_sim=$<TARGET_FILE:fusemap_sim_tool>)
endif()
add_test(NAME tools_exit_codes
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/tools/exit_codes.sh ${tools_exit_code_args})
set_tests_properties(tools_exit_codes PROPERTIES TIMEOUT 120)

# tools/bench_logs.sh --start-at-scan and tools/bench_starts.sh (README "Benchmarks"): need
# every binary bench_logs.sh runs.
if(TARGET fusemap_carmen2lcm AND TARGET fusemap_offline AND TARGET fusemap_eval_tool
   AND TARGET fusemap_bench_images)
  foreach(test_name_and_script "tools_bench_logs_start_at_scan;bench_logs_start_test.sh"
                               "tools_bench_starts;bench_starts_test.sh")
    list(GET test_name_and_script 0 test_name)
    list(GET test_name_and_script 1 script)
    add_test(NAME ${test_name}
             COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/tools/${script}
                     ${PROJECT_SOURCE_DIR} ${CMAKE_BINARY_DIR})
    set_tests_properties(${test_name} PROPERTIES TIMEOUT 120)
  endforeach()
endif()
