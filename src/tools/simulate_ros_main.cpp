// simulate_ros: `simulate` with the ROS layer linked, for --bag and --replay (simulate hands such a run over
// to it).
#include <cstdio>
#include <cstdlib>

#include "rigid_body_sim/ros/bag_recorder.h"
#include "rigid_body_sim/ros/command_log.h"
#include "simulate_cli.h"

int main(int argc, char** argv) {
  const int status =
      rigid_body_sim::runSimulate(argc, argv, rigid_body_sim::bagOpener(), rigid_body_sim::readRecordedRun);
  if (rigid_body_sim::anyBagKeptUnclosed()) {
    // Its one line is said: end without the static destructors, in which class_loader would add a warning
    // about the failed bag's plugin (the bag cannot be destroyed: its destructor writes and throws again).
    std::fflush(nullptr);
    std::_Exit(status);
  }
  return status;
}
