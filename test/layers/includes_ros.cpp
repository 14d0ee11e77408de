// Compiled with a layer's guard (test/CMakeLists.txt): must fail, as a ROS header in the core or io would.
#include <ros/time.h>
