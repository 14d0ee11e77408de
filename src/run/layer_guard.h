// Forced into every source of the run library and of `simulate` (CMakeLists.txt): no ROS header there, so
// that `simulate` loads no ROS library. Every ROS header uses the identifier `ros`, so an include of one
// fails to compile ("attempt to use poisoned").
#pragma GCC poison ros
