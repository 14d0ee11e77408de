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

# --- sim_node on bad input: at start-up (the node started per row by the test) and at run time ---
# (rostest is found by CMakeLists.txt, in the same if)
if(CATKIN_ENABLE_TESTING)
  foreach(rbs_bad_input startup runtime)
    add_rostest_gtest(test_node_bad_input_${rbs_bad_input} test/rostest/bad_input_${rbs_bad_input}.test
                      test/node/test_node_bad_input_${rbs_bad_input}.cpp)
    target_link_libraries(test_node_bad_input_${rbs_bad_input} ${PROJECT_NAME}_adapters ${catkin_LIBRARIES} GTest::gtest)
    add_dependencies(test_node_bad_input_${rbs_bad_input} sim_node)
    target_compile_definitions(test_node_bad_input_${rbs_bad_input} PRIVATE
      RBS_SIM_NODE_EXE="$<TARGET_FILE:sim_node>"
      RBS_BAD_INPUT_DIR="${CMAKE_CURRENT_SOURCE_DIR}/test/bad_input")
  endforeach()
endif()
