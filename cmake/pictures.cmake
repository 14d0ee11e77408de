# pictures (issue 6): rviz for real, under Xvfb, its screenshot checked against the scene the node
# published (test/pictures/rviz_screenshot.sh; the PNG, the regions it checked and its findings are kept in
# test_results/pictures/), and the plot command on a short simulate run and on a bag of sim.launch
# record:=true (test/pictures/test_plot_run.py).
# `make screenshot` and `make pictures` (mk/pictures.mk) write docs/images.
if(CATKIN_ENABLE_TESTING)
  add_test(NAME pictures_rviz_screenshot
    COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/test/pictures/rviz_screenshot.sh
            ${CMAKE_BINARY_DIR} ${CMAKE_BINARY_DIR}/test_results/pictures/rviz.png)
  # Alone: rviz renders with software OpenGL and wants the machine's two cores for itself.
  set_tests_properties(pictures_rviz_screenshot PROPERTIES TIMEOUT 240 RUN_SERIAL TRUE)

  add_test(NAME pictures_plot_run COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/test/pictures/test_plot_run.py)
  set_tests_properties(pictures_plot_run PROPERTIES TIMEOUT 180 ENVIRONMENT
    "RBS_SIMULATE=$<TARGET_FILE:simulate>;RBS_BUILD=${CMAKE_BINARY_DIR}")
endif()
