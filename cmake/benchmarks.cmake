# benchmarks (issue 4): parameter sweeps in the adapters library and their test; `make bench` builds the
# Google Benchmark suite with -Drigid_body_sim_BENCHMARKS=ON (Release) in a build folder of its own.

# Speed of the core (make bench): let the compiler inline the library's own small functions (a step calls
# several) instead of calling them through the PLT. This changes no floating-point operation.
target_compile_options(${PROJECT_NAME}_core PRIVATE -fno-semantic-interposition)

# Sweeps: a thread pool in the adapters library, driven by `simulate --sweep`.
find_package(Threads REQUIRED)
target_sources(${PROJECT_NAME}_adapters PRIVATE src/adapters/sweep.cpp)
target_link_libraries(${PROJECT_NAME}_adapters Threads::Threads)

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(test_sweep test/test_sweep.cpp)
  target_link_libraries(test_sweep ${PROJECT_NAME}_adapters GTest::gtest_main)
  add_dependencies(test_sweep simulate)
  target_compile_definitions(test_sweep PRIVATE
    RBS_SIMULATE_EXE="$<TARGET_FILE:simulate>"
    RBS_CONFIG_DIR="${CMAKE_CURRENT_SOURCE_DIR}/config")
endif()

option(${PROJECT_NAME}_BENCHMARKS "build the Google Benchmark suite of the core (make bench)" OFF)
if(${PROJECT_NAME}_BENCHMARKS)
  find_package(benchmark REQUIRED)
  add_executable(bench_core bench/bench_core.cpp)
  target_link_libraries(bench_core ${PROJECT_NAME}_core benchmark::benchmark)
  target_compile_options(bench_core PRIVATE ${RBS_WARNINGS})
  install(TARGETS bench_core RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
endif()
