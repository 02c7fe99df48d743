# The log writer lives with the fusemap_sim tool (it needs io/, which sits above sim/); its test
# compiles that source and links io.
target_sources(sim_sim_log_test PRIVATE ${PROJECT_SOURCE_DIR}/tools/sim/sim_log.cc)
target_include_directories(sim_sim_log_test PRIVATE ${PROJECT_SOURCE_DIR}/tools/sim)
target_link_libraries(sim_sim_log_test PRIVATE fusemap_io)
