#include "rigid_body_sim/io/replay.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "rigid_body_sim/io/csv_writer.h"
#include "rigid_body_sim/io/node_interface.h"

namespace rigid_body_sim {

namespace {

const std::string kReplay = "(replay)";

std::string describe(std::size_t index, const WorldCommand& command) {
  return "command " + std::to_string(index) + " (" + toString(command.kind) +
         (command.body.empty() ? "" : " of '" + command.body + "'") + " at step " +
         std::to_string(command.step) + ")";
}

void checkStart(const std::vector<WorldCommand>& commands) {
  if (commands.empty() || commands[0].kind != WorldCommand::Kind::Config || commands[0].step != 0) {
    throw ConfigError(kReplay, "commands", commands.empty() ? "(none)" : describe(0, commands[0]),
                      "the config at step 0 first");
  }
}

}  // namespace

ReplaySummary replayRun(const std::vector<WorldCommand>& commands, const OfflineOptions& options,
                        const SinkOpener& open_bag) {
  checkStart(commands);
  const WorldConfig& config = commands[0].world;
  validate(options, config);
  World world(config, node_interface::ownNames());
  const double sample_rate = options.sample_rate > 0.0 ? options.sample_rate : config.publish_rate;
  const auto steps_per_sample = static_cast<std::int64_t>(std::llround(config.rate / sample_rate));
  const auto last_step = static_cast<std::int64_t>(std::floor(options.duration * config.rate + 1e-9));

  ReplaySummary summary;
  const auto note_bodies = [&] {
    for (const auto& body : world.bodies()) {
      const auto& seen = summary.bodies;
      if (std::find(seen.begin(), seen.end(), body.name) == seen.end()) summary.bodies.push_back(body.name);
    }
  };
  note_bodies();
  CsvWriter csv(options.out_dir, world.bodies());
  const std::unique_ptr<SampleSink> bag = openSink(options.bag, config, world.bodies(), open_bag);
  std::size_t next = 1;
  for (std::int64_t count = 0;; ++count) {
    // As in the node: the state at a count is published before the commands at that count apply.
    if (count % steps_per_sample == 0) {
      csv.write(world.time(), world.bodies());
      if (bag) bag->write(world);
    }
    for (; next < commands.size() && commands[next].step <= count; ++next) {
      try {
        world.apply(commands[next]);
      } catch (const ConfigError& error) {
        throw ConfigError(describe(next, commands[next]) + " cannot be applied: " + error.what());
      }
      if (bag) bag->applied(commands[next], next, world);
      ++summary.commands_applied;
      note_bodies();
    }
    if (count == last_step) break;
    world.step();
  }
  csv.commit();
  if (bag) bag->commit();
  summary.end_time = world.time();
  summary.steps = world.stepCount();
  return summary;
}

std::string formatSummary(const ReplaySummary& summary) {
  std::ostringstream out;
  out << "replayed " << summary.end_time << " s in " << summary.steps << " steps with "
      << summary.commands_applied << " commands after the config; bodies:";
  for (const auto& body : summary.bodies) out << " " << body;
  out << "\n";
  return out.str();
}

}  // namespace rigid_body_sim
