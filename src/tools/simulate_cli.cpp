#include "simulate_cli.h"

#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "rigid_body_sim/io/config_loader.h"
#include "rigid_body_sim/io/sweep.h"

namespace rigid_body_sim {

namespace {

const std::string kCommandLine = "(command line)";
// The program that writes bags, installed beside `simulate`.
const char* const kRosProgram = "simulate_ros";

struct SweepArgs {
  std::vector<std::string> specs;
  std::string shard;
  int jobs = 0;
};

// --jobs, --shard and --bag only make sense with (resp. without) --sweep: refuse rather than ignore.
void checkModes(const SweepArgs& args, const OfflineOptions& options) {
  if (args.jobs < 0 || args.jobs > 4096) {
    throw ConfigError(kCommandLine, "--jobs", std::to_string(args.jobs), "0 (every core) to 4096 threads");
  }
  if (args.specs.empty() && args.jobs != 0) {
    throw ConfigError(kCommandLine, "--jobs", std::to_string(args.jobs), "only with --sweep");
  }
  if (args.specs.empty() && !args.shard.empty()) {
    throw ConfigError(kCommandLine, "--shard", "'" + args.shard + "'", "only with --sweep");
  }
  if (!args.specs.empty() && !options.bag.empty()) {
    throw ConfigError(kCommandLine, "--bag", "'" + options.bag + "'",
                      "no bag with --sweep (run one variant for a bag)");
  }
}

// "1 thread", "3 threads".
std::string counted(std::int64_t n, const std::string& noun) {
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

void sweep(const WorldConfig& config, const SweepArgs& args, const OfflineOptions& options) {
  SweepOptions sweep;
  for (const auto& spec : args.specs) sweep.axes.push_back(parseSweepAxis(spec, config));
  if (!args.shard.empty()) sweep.shard = parseShard(args.shard);
  sweep.jobs = static_cast<unsigned>(args.jobs);
  const auto start = std::chrono::steady_clock::now();
  const auto result = runSweep(config, sweep, options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto count = result.end - result.first;
  if (count == 0) {
    std::cout << "swept none of " << counted(result.total, "variant") << ": this shard is empty -> "
              << result.path << "\n";
    return;
  }
  std::cout << "swept " << count << " of " << counted(result.total, "variant") << " (" << result.first
            << " to " << result.end - 1 << ") on " << counted(result.jobs, "thread") << " in " << seconds
            << " s (" << static_cast<double>(count) / seconds << " variants/s) -> " << result.path << "\n";
}

// Replaces this process with simulate_ros on the same arguments; returns only on failure.
void handOverToRosProgram(char** argv) {
  const auto program = std::filesystem::read_symlink("/proc/self/exe").parent_path() / kRosProgram;
  execv(program.c_str(), argv);
  throw std::runtime_error("--bag and --replay need " + program.string() + ": " + std::strerror(errno));
}

// Exactly one of CONFIG and --replay; no sweep of a replay.
void checkSource(const std::string& config_path, const std::string& replay, const SweepArgs& args) {
  if (config_path.empty() && replay.empty()) {
    throw ConfigError("CONFIG is required (simulate --help lists the options)");
  }
  if (!config_path.empty() && !replay.empty()) {
    throw ConfigError(kCommandLine, "CONFIG", "'" + config_path + "'",
                      "no CONFIG with --replay (the bag has it)");
  }
  if (!replay.empty() && !args.specs.empty()) {
    throw ConfigError(kCommandLine, "--sweep", "'" + args.specs[0] + "'", "no sweep with --replay");
  }
}

// --replay: the run of a bag's commands, for its duration unless --duration says otherwise.
void replay(const std::string& bag, bool duration_given, OfflineOptions options, const RunReader& read_run,
            const SinkOpener& open_bag) {
  const RecordedRun run = read_run(bag);
  if (!duration_given) options.duration = run.end_time;
  std::cout << formatSummary(replayRun(run.commands, options, open_bag));
}

}  // namespace

int runSimulate(int argc, char** argv, const SinkOpener& open_bag, const RunReader& read_run) {
  CLI::App app{"Offline rigid_body_sim run: CSV per body, optional bag, no ROS master needed.", "simulate"};
  std::string config_path;
  OfflineOptions options;
  SweepArgs sweep_args;
  std::string replay_bag;
  app.add_option("CONFIG", config_path, "YAML configuration (the node's parameters)");
  app.add_option(
      "--replay", replay_bag,
      "rebuild the run recorded in this bag from its /sim/commands instead of a CONFIG (duration: the "
      "bag's)");
  app.add_option("--duration", options.duration, "simulated seconds")->capture_default_str();
  app.add_option("--sample-rate", options.sample_rate,
                 "samples per simulated second, a divisor of rate (default: publish_rate)");
  app.add_option("--out-dir", options.out_dir, "folder for <body>.csv (or sweep.csv)")->capture_default_str();
  app.add_option("--bag", options.bag, "also write what the node would publish into this bag");
  app.add_option(
         "--sweep", sweep_args.specs,
         "BODY.KEY=START:STOP:N: N values from START to STOP inclusive; repeat for a Cartesian product")
      ->allow_extra_args(false);  // one value per --sweep, so that CONFIG may follow
  app.add_option("--jobs", sweep_args.jobs, "threads for --sweep (default 0: every core)");
  app.add_option("--shard", sweep_args.shard, "i/n: run only slice i of n of the sweep (1 <= i <= n)");
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "simulate: " + std::string(e.what()) + " (simulate --help lists the options)\n";
  });
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    // --help is a ParseError too: it prints the help and exits 0; every other one is the user's mistake.
    return app.exit(error) == 0 ? 0 : 1;
  }

  try {
    checkSource(config_path, replay_bag, sweep_args);
    checkModes(sweep_args, options);
    if ((!options.bag.empty() || !replay_bag.empty()) && !open_bag) handOverToRosProgram(argv);
    if (!replay_bag.empty()) {
      replay(replay_bag, app.count("--duration") > 0, options, read_run, open_bag);
      return 0;
    }
    const auto config = loadWorldConfigFile(config_path);
    for (const auto& note : autoSubstepNotes(config)) std::cerr << "simulate: note: " << note << "\n";
    for (const auto& warning : slowRunWarnings(config)) std::cerr << "simulate: warning: " << warning << "\n";
    if (!sweep_args.specs.empty()) {
      sweep(config, sweep_args, options);
    } else {
      std::cout << formatSummary(runOffline(config, options, open_bag));
    }
  } catch (const std::exception& error) {
    std::cerr << "simulate: " << error.what() << "\n";
    return 1;
  }
  return 0;
}

}  // namespace rigid_body_sim
