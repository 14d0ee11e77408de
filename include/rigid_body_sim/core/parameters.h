// Validated configuration of bodies and of the world: a body's config is one of the registered body types'
// (core/body_types.h), whose descriptions know every key, its range and its names; here the world's keys and
// the checks that concern the whole world.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "rigid_body_sim/core/body_key.h"
#include "rigid_body_sim/core/body_types.h"
#include "rigid_body_sim/core/constants.h"

namespace rigid_body_sim {

// The key whose initial value state field `field` takes (x: x0), or null.
template <class Config>
const BodyKey<Config>* keyOfStateField(const std::string& field) {
  for (const auto& key : bodyType<Config>().keys) {
    if (key.state_field && field == key.state_field) return &key;
  }
  return nullptr;
}

struct BodyConfig {
  std::string name;  // also the TF frame and the topic namespace
  AnyBodyConfig config;
};

// Its type's name: rod, roller or block.
std::string typeName(const BodyConfig& body);

// True when a key of level Restart differs (the body restarts), false when only parameters changed.
template <class Config>
bool initialChanged(const Config& a, const Config& b) {
  for (const auto& key : bodyType<Config>().keys) {
    if (key.change == KeyChange::Restart && key.written() && key.text(a) != key.text(b)) return true;
  }
  return false;
}

// The most bodies a world holds, from its config file or spawned while it runs: each brings a thread-safe
// publisher, a reconfigure server and markers to the node, and a CSV file to `simulate`.
constexpr std::size_t kMaxBodies = 1000;

struct WorldConfig {
  double rate = 1000.0;              // physics steps per simulated second
  double publish_rate = 50.0;        // samples per simulated second
  double gravity = kDefaultGravity;  // copied into every body
  std::string world_frame = "world";
  // A race: the bodies on slopes (the types with kRaces) start together, each stops at the end of its slope,
  // and all start a new lap together once every one has finished and the results have stood 2 s
  // (World::step); false: each restarts alone at the end of its slope.
  bool race = false;
  std::vector<BodyConfig> bodies;
};

// The world's keys in a config file, in the order of WorldConfig.
const std::vector<std::string>& worldKeys();

// World-level ranges.
Range rateRange();
Range publishRateRange();
Range gravityRange();

// Checks the world keys, every body, name validity (core/names.h), that every TF frame (world_frame, each
// body and its fixed frame) is distinct, that there are 1 to kMaxBodies bodies, and that publish_rate divides
// rate. A body cannot be named like a world key nor like one of `reserved_names`: the names of the node's
// private namespace, which the bodies share (its options, topics and services; a body named `rate` would
// shadow the world's rate).
void validate(const WorldConfig& config, const std::vector<std::string>& reserved_names = {});

// Sub-steps per simulated second above which a valid config is reported as slow.
constexpr double kSlowSubstepsPerSecond = 1e7;

// One human line per body of a validated config that makes the run slow (a stiff rod needing many
// sub-steps per step); empty when nothing is slow. Pure: the caller decides where to print.
std::vector<std::string> slowRunWarnings(const WorldConfig& config);

// One human line per rod of a validated config whose `substeps: auto` splits its steps: into how many
// sub-steps and why. Empty when auto splits nothing (the text's values). Pure, as slowRunWarnings.
std::vector<std::string> autoSubstepNotes(const WorldConfig& config);

// True when `divisor` divides `rate` to rounding: rate / divisor is a whole number >= 1.
bool dividesRate(double rate, double divisor);
}  // namespace rigid_body_sim
