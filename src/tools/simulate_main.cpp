// simulate CONFIG.yaml [--duration S] [--sample-rate HZ] [--out-dir DIR] [--bag FILE]
//                      [--sweep BODY.KEY=START:STOP:N ...] [--jobs J] [--shard i/n]
// Runs the node's physics without a ROS master and writes DIR/<body>.csv, or, with --sweep, runs every
// variant on a thread pool and writes one summary row per variant. Links no ROS library: a run with --bag
// is handed over to simulate_ros.
#include "simulate_cli.h"

int main(int argc, char** argv) { return rigid_body_sim::runSimulate(argc, argv, nullptr); }
