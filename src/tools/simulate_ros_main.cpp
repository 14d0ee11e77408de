// simulate_ros: `simulate` with the ROS layer linked, for --bag and --replay (simulate hands such a run over
// to it).
#include "rigid_body_sim/ros/bag_recorder.h"
#include "rigid_body_sim/ros/command_log.h"
#include "simulate_cli.h"

int main(int argc, char** argv) {
  return rigid_body_sim::runSimulate(argc, argv, rigid_body_sim::openBag, rigid_body_sim::readRecordedRun);
}
