#include "simulate_cli.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

#include <boost/program_options.hpp>

#include "rigid_body_sim/io/config_loader.h"
#include "rigid_body_sim/run/sweep.h"

namespace rigid_body_sim {

namespace {

namespace po = boost::program_options;

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

// What the command line asks for, before any check of the values.
struct CommandLine {
  std::string config_path;
  std::string replay_bag;
  OfflineOptions options;
  SweepArgs sweep;
  bool duration_given = false;  // replay takes the bag's end time otherwise
  bool help = false;
  bool check = false;
};

const char* const kDescription =
    "Offline rigid_body_sim run: CSV per body, optional bag, no ROS master needed.";
const char* const kConfigHelp = "YAML configuration (the node's parameters)";

// The options, writing straight into `line` on po::notify. CONFIG is no option here: it is the one token
// that is not an option (collectConfig), so that `--config` does not exist.
po::options_description describeOptions(CommandLine& line) {
  po::options_description options("Options", 110);
  OfflineOptions& run = line.options;
  auto add = options.add_options();
  add("help,h", "print this help message and exit");
  add("check", po::bool_switch(&line.check),
      "only load and validate CONFIG as the node does: exit 0 if accepted, 1 with the refusal");
  add("replay", po::value(&line.replay_bag)->value_name("BAG"),
      "rebuild the run recorded in this bag from its /sim/commands instead of a CONFIG (duration: the "
      "bag's)");
  add("duration", po::value(&run.duration)->value_name("S")->default_value(run.duration),
      "simulated seconds");
  add("sample-rate", po::value(&run.sample_rate)->value_name("HZ"),
      "samples per simulated second, a divisor of rate (default: publish_rate)");
  add("out-dir", po::value(&run.out_dir)->value_name("DIR")->default_value(run.out_dir),
      "folder for <body>.csv (or sweep.csv)");
  add("bag", po::value(&run.bag)->value_name("FILE"), "also write what the node would publish into this bag");
  // One value per --sweep (no multitoken), so that CONFIG may follow one.
  add("sweep", po::value(&line.sweep.specs)->value_name("SPEC"),
      "BODY.KEY=START:STOP:N: N values from START to STOP inclusive; repeat for a Cartesian product");
  add("jobs", po::value(&line.sweep.jobs)->value_name("J"), "threads for --sweep (default 0: every core)");
  add("shard", po::value(&line.sweep.shard)->value_name("i/n"),
      "run only slice i of n of the sweep (1 <= i <= n)");
  return options;
}

void printHelp(const po::options_description& options) {
  const auto width = static_cast<int>(options.get_option_column_width());
  std::cout << kDescription << "\nUsage: simulate [OPTIONS] [CONFIG]\n\nPositionals:\n  " << std::left
            << std::setw(width - 2) << "CONFIG" << kConfigHelp << "\n\n"
            << options << "\n";
}

// The tokens that are no option (and no option's value) are CONFIG: at most one.
void collectConfig(const po::parsed_options& parsed, CommandLine& line) {
  std::vector<std::string> positionals;
  for (const auto& option : parsed.options) {
    if (option.position_key >= 0)
      positionals.insert(positionals.end(), option.value.begin(), option.value.end());
  }
  if (positionals.size() > 1) {
    throw po::error("unexpected argument '" + positionals[1] + "' after CONFIG '" + positionals[0] + "'");
  }
  if (!positionals.empty()) line.config_path = positionals[0];
}

// Fills `line` through `options` (describeOptions(line)); throws po::error on a malformed command line
// (unknown option, missing or non-numeric value, an option given twice).
void parseCommandLine(int argc, char** argv, const po::options_description& options, CommandLine& line) {
  // No guessing: CLI11 took no abbreviation (--dur) either. A value may still start with '-' (--duration -1).
  const auto style = po::command_line_style::default_style & ~po::command_line_style::allow_guessing;
  const auto parsed = po::command_line_parser(argc, argv).options(options).style(style).run();
  po::variables_map values;
  po::store(parsed, values);
  po::notify(values);
  collectConfig(parsed, line);
  line.duration_given = values.count("duration") > 0 && !values["duration"].defaulted();
  line.help = values.count("help") > 0;
}

// --help wins over any mistake elsewhere on the line (CLI11: over all but a value that is no number).
bool asksForHelp(int argc, char** argv) {
  return std::any_of(argv + 1, argv + argc, [](const char* arg) {
    return std::strcmp(arg, "--help") == 0 || std::strcmp(arg, "-h") == 0;
  });
}

int run(const CommandLine& line, char** argv, const SinkOpener& open_bag, const RunReader& read_run) {
  const OfflineOptions& options = line.options;
  checkSource(line.config_path, line.replay_bag, line.sweep);
  checkModes(line.sweep, options);
  if (line.check && (!line.replay_bag.empty() || !line.sweep.specs.empty() || !options.bag.empty())) {
    throw ConfigError(kCommandLine, "--check", "with --replay, --sweep or --bag", "with a CONFIG alone");
  }
  if ((!options.bag.empty() || !line.replay_bag.empty()) && !open_bag) handOverToRosProgram(argv);
  if (!line.replay_bag.empty()) {
    replay(line.replay_bag, line.duration_given, options, read_run, open_bag);
    return 0;
  }
  const auto config = loadWorldConfigFile(line.config_path);
  if (line.check) {
    validate(options, config);  // --check answers for the run this line asks for, options included
    std::cout << line.config_path << ": accepted, bodies:";
    for (const auto& body : config.bodies) std::cout << ' ' << body.name;
    std::cout << "\n";
    return 0;
  }
  for (const auto& note : autoSubstepNotes(config)) std::cerr << "simulate: note: " << note << "\n";
  for (const auto& warning : slowRunWarnings(config)) std::cerr << "simulate: warning: " << warning << "\n";
  if (!line.sweep.specs.empty()) {
    sweep(config, line.sweep, options);
  } else {
    std::cout << formatSummary(runOffline(config, options, open_bag));
  }
  return 0;
}

}  // namespace

int runSimulate(int argc, char** argv, const SinkOpener& open_bag, const RunReader& read_run) {
  CommandLine line;
  const po::options_description options = describeOptions(line);
  try {
    parseCommandLine(argc, argv, options, line);
  } catch (const po::error& error) {
    if (asksForHelp(argc, argv)) {
      printHelp(options);
      return 0;
    }
    std::cerr << "simulate: " << error.what() << " (simulate --help lists the options)\n";
    return 1;
  }
  if (line.help) {
    printHelp(options);
    return 0;
  }
  try {
    return run(line, argv, open_bag, read_run);
  } catch (const std::exception& error) {
    std::cerr << "simulate: " << error.what() << "\n";
    return 1;
  }
}

}  // namespace rigid_body_sim
