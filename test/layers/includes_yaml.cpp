// Compiled with the core's guard (test/CMakeLists.txt): must fail, as yaml-cpp in the core would.
#include <yaml-cpp/yaml.h>
