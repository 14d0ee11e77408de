// simulate CONFIG.yaml [--duration S] [--sample-rate HZ] [--out-dir DIR] [--bag FILE]
//                      [--sweep BODY.KEY=START:STOP:N ...] [--jobs J] [--shard i/n]
// simulate --replay BAG [--duration S] [--sample-rate HZ] [--out-dir DIR] [--bag FILE]
// Runs the node's physics without a ROS master and writes DIR/<body>.csv, or, with --sweep, runs every
// variant on a thread pool and writes one summary row per variant, or, with --replay, rebuilds a recorded run
// from its /sim/commands. Links no ROS library: a run with --bag or --replay is handed over to simulate_ros.
#include "simulate_cli.h"

int main(int argc, char** argv) { return rigid_body_sim::runSimulate(argc, argv, nullptr, nullptr); }
