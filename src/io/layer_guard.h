// Forced into every source of the io library (CMakeLists.txt): no ROS header there, so that `simulate`,
// which links it, loads no ROS library. Every ROS header uses the identifier `ros`, so an include of one
// fails to compile ("attempt to use poisoned").
#pragma GCC poison ros
