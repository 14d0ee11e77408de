// Forced into every source of the core library (CMakeLists.txt). The core includes no ROS header and no
// YAML: every ROS header uses the identifier `ros` and yaml-cpp's use `YAML`, so an include of one fails
// to compile here ("attempt to use poisoned"). On Debian those headers sit in /usr/include, where an
// include path cannot hide them.
#pragma GCC poison ros YAML
