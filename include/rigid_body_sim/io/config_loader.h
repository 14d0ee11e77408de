// YAML (a file, or a node converted from the ROS parameter server) -> validated WorldConfig.
// The node and `simulate` both load through here, so a file behaves the same in either.
#pragma once

#include <string>

#include <yaml-cpp/yaml.h>

#include "rigid_body_sim/core/command.h"
#include "rigid_body_sim/core/parameters.h"

namespace rigid_body_sim {

// Parses and validates; throws ConfigError with one line naming the body, key, value and range. A body
// may take neither a world key nor one of the node's own names (core/node_interface.h).
WorldConfig parseWorldConfig(const YAML::Node& root);

// The refusal of a text where a number or a boolean is asked: a quoted scalar in a file, a str from Python.
ConfigError quotedTextRefusal(const std::string& body, const std::string& key, const std::string& text,
                              const std::string& allowed);

// Parses YAML text (`source` names it in messages); a YAML syntax error is a ConfigError too.
WorldConfig parseWorldConfigText(const std::string& text, const std::string& source);

// A body's YAML map as a config file's `bodies` holds it (the same keys, defaults and checks of the body
// alone; the world checks names and frames and sets its gravity), named `name`. A YAML syntax error is a
// ConfigError too.
BodyConfig parseBodyText(const std::string& name, const std::string& text);

// A state to set on a body: a YAML map of numbers by state field name (x: 1.5). Names and
// ranges are the world's to check (World::apply); here: a map, of numbers, finite or not.
std::vector<StateValue> parseStateText(const std::string& body, const std::string& text);

// Reads a file; a missing file or a YAML syntax error is a ConfigError too.
WorldConfig loadWorldConfigFile(const std::string& path);

}  // namespace rigid_body_sim
