#include "rigid_body_sim/run/replay.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "rigid_body_sim/core/node_interface.h"

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

// Adds to `seen` the bodies of `world` it does not hold yet.
void noteBodies(const World& world, std::vector<std::string>& seen) {
  for (const auto& body : world.bodies()) {
    if (std::find(seen.begin(), seen.end(), body.name) == seen.end()) seen.push_back(body.name);
  }
}

// Advances to the command's step and applies it there: the states on the way (and at that step, if it is
// a sampling instant) are sampled before it, as the node published them.
void applyAtItsStep(Session& session, const WorldCommand& command, std::size_t index) {
  const std::int64_t now = session.world().stepCount();
  if (command.step < now) {
    throw ConfigError(describe(index, command) + " cannot be applied: the replay is at step " +
                      std::to_string(now) + " already (the commands in the order of their steps)");
  }
  session.advance(command.step - now);
  try {
    session.apply(command);
  } catch (const ConfigError& error) {
    throw ConfigError(describe(index, command) + " cannot be applied: " + error.what());
  }
}

}  // namespace

ReplaySummary replayRun(const std::vector<WorldCommand>& commands, const OfflineOptions& options,
                        const SinkOpener& open_bag) {
  checkStart(commands);
  const WorldConfig& config = commands[0].world;
  validate(options, config);
  Session session(config, node_interface::ownNames(), stepsPerSample(options, config));
  const auto last_step = static_cast<std::int64_t>(std::floor(options.duration * config.rate + 1e-9));

  ReplaySummary summary;
  noteBodies(session.world(), summary.bodies);
  RunFiles files(options.out_dir, options.bag, config, session.world().bodies(), open_bag);
  session.addSink(files);
  session.sampleNow();  // t = 0
  for (std::size_t next = 1; next < commands.size() && commands[next].step <= last_step; ++next) {
    applyAtItsStep(session, commands[next], next);
    noteBodies(session.world(), summary.bodies);
  }
  session.advance(last_step - session.world().stepCount());
  files.commit();
  summary.end_time = session.world().time();
  summary.steps = session.world().stepCount();
  summary.commands_applied = session.commandsApplied();
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
