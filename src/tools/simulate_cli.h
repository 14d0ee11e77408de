// The whole of `simulate`, shared by its two programs: `simulate`, which links no ROS library, and
// `simulate_ros`, the same tool linked with the ROS layer for --bag. `simulate` hands a run with --bag
// over to `simulate_ros` beside it (execv, the same arguments), so that a run without a bag never loads
// roscpp or rosbag.
#pragma once

#include "rigid_body_sim/io/offline_run.h"

namespace rigid_body_sim {

// Parses the command line, runs (or sweeps) and returns the exit status; `open_bag` is null in `simulate`.
int runSimulate(int argc, char** argv, const SinkOpener& open_bag);

}  // namespace rigid_body_sim
