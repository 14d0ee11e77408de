// YAML (a file, or a node converted from the ROS parameter server) -> validated WorldConfig.
// The node and `simulate` both load through here, so a file behaves the same in either.
#pragma once

#include <string>

#include <yaml-cpp/yaml.h>

#include "rigid_body_sim/core/parameters.h"

namespace rigid_body_sim {

// Parses and validates; throws ConfigError with one line naming the body, key, value and range. A body
// may take neither a world key nor one of the node's own names (io/node_interface.h).
WorldConfig parseWorldConfig(const YAML::Node& root);

// Parses YAML text (`source` names it in messages); a YAML syntax error is a ConfigError too.
WorldConfig parseWorldConfigText(const std::string& text, const std::string& source);

// Reads a file; a missing file or a YAML syntax error is a ConfigError too.
WorldConfig loadWorldConfigFile(const std::string& path);

// The theta0 drawn for a rod from `seed` when theta0 is not given: 2 pi u, u uniform in [0, 1) from
// the first output of std::mt19937_64(seed) (portable, unlike std::uniform_real_distribution).
double theta0FromSeed(unsigned long long seed);

}  // namespace rigid_body_sim
