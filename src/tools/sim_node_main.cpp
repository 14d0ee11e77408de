// sim_node: steps the configured bodies at `rate` in simulated time and publishes TF, markers and states.
#include <clocale>

#include <ros/ros.h>

#include "rigid_body_sim/core/node_interface.h"
#include "rigid_body_sim/node/sim_node.h"
#include "rigid_body_sim/ros/launch_end.h"

int main(int argc, char** argv) {
  // rosconsole's log4cxx passes every line (console, /rosout) through the C library's character set, and a
  // program starts in the "C" locale, ASCII, whatever LANG says: a refused name such as 'ünï' would reach
  // the log as '??n??'. ROS strings are UTF-8; the character classes only (LC_CTYPE), numbers keep C's
  // format.
  const bool utf8 = std::setlocale(LC_CTYPE, "C.UTF-8") != nullptr;
  ros::init(argc, argv, "sim");
  if (!utf8) ROS_WARN("no C.UTF-8 locale: a name or value that is not ASCII shows as '?' in this node's log");
  // These handles outlive the node: when the last NodeHandle goes, roscpp shuts down and rosconsole with
  // it, so a refusal thrown from SimNode's constructor could no longer be logged.
  const ros::NodeHandle node;
  const ros::NodeHandle private_node("~");
  try {
    rigid_body_sim::SimNode sim(node, private_node);
    return sim.run();
  } catch (const rigid_body_sim::ConfigError& error) {
    ROS_FATAL_STREAM("refused config: " << error.what());
    // sim.launch ends with its node, whatever its duration: a refused config must not leave it running.
    if (ros::param::param("~" + std::string(rigid_body_sim::node_interface::kEndLaunch), false)) {
      rigid_body_sim::endParentRoslaunch();
    }
    return 1;
  }
}
