// The node's private parameters -> the same YAML tree a config file gives, so that one loader serves both.
#pragma once

#include <set>
#include <string>

#include <xmlrpcpp/XmlRpcValue.h>
#include <yaml-cpp/yaml.h>

namespace rigid_body_sim {

// Converts a parameter-server value (maps, lists, numbers, strings, booleans) to YAML.
YAML::Node toYaml(XmlRpc::XmlRpcValue& value);

// The config part of the node's private namespace: the world keys only, leaving out the node's own
// options and the namespaces of the reconfigure servers (`ignored`). Any other key stays, so that the
// loader refuses a typo.
YAML::Node configFromParams(XmlRpc::XmlRpcValue& private_namespace, const std::set<std::string>& ignored);

}  // namespace rigid_body_sim
