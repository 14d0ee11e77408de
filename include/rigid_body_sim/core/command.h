// A change of the world while it runs (WorldCommand: the message that carries one is rigid_body_sim/Command):
// the one value that every way of changing a running world builds (the node's services and reconfigure
// servers, a replay of a recorded run) and World::apply takes.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rigid_body_sim/core/parameters.h"

namespace rigid_body_sim {

// One state field set by a SetState command, named as in the CSV: one of the body's settableStateFields
// (core/state_fields.h).
struct StateValue {
  std::string field;
  double value = 0.0;
};

struct WorldCommand {
  enum class Kind { Config, Reconfigure, Spawn, Delete, SetState, Reset };
  Kind kind = Kind::Reset;
  // Applies while the world's step count is `step`, before the step to step + 1.
  std::int64_t step = 0;
  std::string body;               // Reconfigure, Spawn, Delete, SetState
  WorldConfig world;              // Config: the whole world
  BodyConfig config;              // Reconfigure, Spawn: the body's whole new config (config.name == body)
  std::vector<StateValue> state;  // SetState: the fields to set, each at most once
};

std::string toString(WorldCommand::Kind kind);  // config, reconfigure, spawn, delete, set_state, reset
std::optional<WorldCommand::Kind> commandKindFromString(const std::string& name);

// The one line that reports a refused change (`kind` as toString writes it, `body` empty for none, `why` the
// ConfigError's): the node's WARN line and its services' message, the Python module's ValueError.
std::string refusalLine(const std::string& kind, const std::string& body, const std::string& why);

}  // namespace rigid_body_sim
