// sim_node: steps the configured bodies at `rate` in simulated time and publishes TF, markers and states.
#include <ros/ros.h>

#include "rigid_body_sim/node/sim_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "sim");
  try {
    rigid_body_sim::SimNode node(ros::NodeHandle(), ros::NodeHandle("~"));
    node.run();
  } catch (const rigid_body_sim::ConfigError& error) {
    ROS_FATAL_STREAM("refused config: " << error.what());
    return 1;
  }
  return 0;
}
