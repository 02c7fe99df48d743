# The cloud evaluator lives with the fusemap_cloudeval tool (it needs the simulator's world,
# which the cloud library must not depend on); its test compiles that source and links sim.
if(TARGET cloud_cloud_eval_test)
  target_sources(cloud_cloud_eval_test PRIVATE ${PROJECT_SOURCE_DIR}/tools/cloudeval/cloud_eval.cc
                                               ${PROJECT_SOURCE_DIR}/tools/cloudeval/landmark_eval.cc)
  target_include_directories(cloud_cloud_eval_test PRIVATE ${PROJECT_SOURCE_DIR}/tools/cloudeval)
  target_link_libraries(cloud_cloud_eval_test PRIVATE fusemap_sim)
endif()
