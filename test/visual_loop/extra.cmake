# The real-image tests read PNG/JPEG files; the library itself never touches files.
if(TARGET visual_loop_real_images_test)
  target_link_libraries(visual_loop_real_images_test PRIVATE opencv_imgcodecs)
endif()
