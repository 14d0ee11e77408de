// A run rebuilt from its commands alone (`simulate --replay`): the world of the first (the config), then
// every command at its step, sampled into the same CSV files as a run of a config.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "rigid_body_sim/core/world.h"
#include "rigid_body_sim/run/offline_run.h"

namespace rigid_body_sim {

// What a recording holds for a replay: its commands in order, and the simulated time of its last message.
struct RecordedRun {
  std::vector<WorldCommand> commands;
  double end_time = 0.0;
};

// Reads a recording (the ROS layer reads bags: ros/command_log.h); throws ConfigError with one line.
using RunReader = std::function<RecordedRun(const std::string& path)>;

struct ReplaySummary {
  double end_time = 0.0;
  std::int64_t steps = 0;
  std::size_t commands_applied = 0;
  std::vector<std::string> bodies;  // every body that existed at some point: each has its CSV file
};

// Runs a Session (run/session.h) of the config from count 0 to options.duration, applying every command at
// its step: the sample of a count (when it is a sampling instant, t = j / sample_rate) comes before the
// commands at that count, as the node publishes. options.bag, if set, is written through `open_bag` as
// `simulate --bag` writes one, with every command in it. Throws ConfigError (one line) when the first
// command is not the config at step 0, or a command cannot be applied (named by its index, kind, body and
// step; a step before the previous command's too), std::runtime_error on an output failure (also for
// options.bag without `open_bag`). The CSV files and the bag are only final when the whole replay succeeds.
ReplaySummary replayRun(const std::vector<WorldCommand>& commands, const OfflineOptions& options,
                        const SinkOpener& open_bag = nullptr);

std::string formatSummary(const ReplaySummary& summary);

}  // namespace rigid_body_sim
