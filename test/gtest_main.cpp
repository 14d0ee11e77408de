// main() of the unit suites. catkin_add_gtest links gtest but, depending on the catkin (Debian's patched one,
// upstream's on Noetic) and on where gtest comes from (a library, /usr/src/googletest), gtest_main under
// different names or not at all; this one is the same everywhere.
#include <gtest/gtest.h>

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
