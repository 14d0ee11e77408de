# reliability (issue 5): extreme values against the core, bad input at every entry point (simulate, and
# sim_node at start-up and at run time). The fuzzer and the sanitizer build live in mk/reliability.mk.
if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(test_extremes test/test_extremes.cpp)
  target_link_libraries(test_extremes ${PROJECT_NAME}_core GTest::gtest_main)

  catkin_add_gtest(test_bad_input_simulate test/test_bad_input_simulate.cpp)
  target_link_libraries(test_bad_input_simulate ${PROJECT_NAME}_adapters GTest::gtest_main)
  add_dependencies(test_bad_input_simulate simulate)
  target_compile_definitions(test_bad_input_simulate PRIVATE
    RBS_SIMULATE_EXE="$<TARGET_FILE:simulate>"
    RBS_BAD_INPUT_DIR="${CMAKE_CURRENT_SOURCE_DIR}/test/bad_input")
endif()
