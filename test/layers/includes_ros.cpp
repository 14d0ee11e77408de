// Compiled with a layer's guard (test/CMakeLists.txt): must fail, as a ROS header in a guarded layer would.
#include <ros/time.h>
