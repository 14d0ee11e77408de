# Faults (issue 5, node side): the NaN guard, respawn, and recordings that survive Ctrl-C and kill -9.
# The soak (make soak, mk/soak.mk) is not a test: it runs for a simulated hour.
if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(test_finite_guard test/test_finite_guard.cpp)
  target_link_libraries(test_finite_guard ${PROJECT_NAME}_adapters GTest::gtest_main)

  # rostests: gtest nodes in test/node driving sim_node.
  foreach(rbs_fault_test guard respawn)
    add_rostest_gtest(test_node_${rbs_fault_test} test/rostest/${rbs_fault_test}.test
                      test/node/test_node_${rbs_fault_test}.cpp)
    target_link_libraries(test_node_${rbs_fault_test} ${PROJECT_NAME}_adapters ${catkin_LIBRARIES} GTest::gtest)
    add_dependencies(test_node_${rbs_fault_test} sim_node)
  endforeach()
  # The same gtest node with use_sim_time (time goes back at the respawn).
  add_rostest(test/rostest/respawn_sim_time.test DEPENDENCIES test_node_respawn)
endif()

# Recording through sim.launch when a run ends badly: Ctrl-C (the bag closed, every sample in it) and
# kill -9 of the recorder (rosbag reindex recovers all but the last chunk). Scripts, about 20 s each.
if(CATKIN_ENABLE_TESTING)
  foreach(rbs_record_fault sigint kill9)
    add_test(NAME record_${rbs_record_fault}
             COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/test/faults/record_faults.sh ${rbs_record_fault}
                     ${CATKIN_DEVEL_PREFIX})
    set_tests_properties(record_${rbs_record_fault} PROPERTIES TIMEOUT 180)
  endforeach()
endif()
