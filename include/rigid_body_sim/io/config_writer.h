// WorldConfig, body configs and commands -> YAML text that the config loader reads back to the same values,
// bit for bit (numbers in their shortest round-trip form, formatNumber). What ~get_config returns and what
// ~commands carries.
#pragma once

#include <cstdint>
#include <string>

#include "rigid_body_sim/core/command.h"

namespace rigid_body_sim {

// A config file of the world: world keys, then each body as one flow map under `bodies`.
std::string toYaml(const WorldConfig& config);

// A body's keys as in a config file, as one flow map: {type: rod, length: 1, ...}.
std::string toYaml(const BodyConfig& body);

// A SetState's fields as one flow map: {x: 1.5, omega: 0}.
std::string toYaml(const std::vector<StateValue>& state);

// A command's payload: the world (config), the body's whole config (reconfigure, spawn), the state set
// (set_state); empty for delete and reset.
std::string payloadYaml(const WorldCommand& command);

// The command that `kind`, `step`, `body` and the payload `yaml` (payloadYaml's) describe; throws ConfigError
// (one line) for an unknown kind or a payload that does not parse as that kind's.
WorldCommand commandFromText(const std::string& kind, std::int64_t step, const std::string& body,
                             const std::string& yaml);

}  // namespace rigid_body_sim
