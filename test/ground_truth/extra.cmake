# The detector tests read JPEG fixtures and render tags (image_u8_* lives in apriltag-utils);
# neither is part of the library itself.
foreach(gt_test ground_truth_tag_detector_test ground_truth_tag_pose_test
                ground_truth_tag_ground_truth_test)
  if(TARGET ${gt_test})
    target_link_libraries(${gt_test} PRIVATE opencv_imgcodecs apriltag::apriltag-utils)
  endif()
endforeach()
