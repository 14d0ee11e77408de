// The whole of `simulate`, shared by its two programs: `simulate`, which links no ROS library, and
// `simulate_ros`, the same tool linked with the ROS layer for --bag and --replay. `simulate` hands such a run
// over to `simulate_ros` beside it (execv, the same arguments), so that a run without a bag never loads
// roscpp or rosbag.
#pragma once

#include "rigid_body_sim/run/offline_run.h"
#include "rigid_body_sim/run/replay.h"

namespace rigid_body_sim {

// Parses the command line, runs (sweeps, replays) and returns the exit status; `open_bag` and `read_run`
// are null in `simulate`.
int runSimulate(int argc, char** argv, const SinkOpener& open_bag, const RunReader& read_run);

}  // namespace rigid_body_sim
