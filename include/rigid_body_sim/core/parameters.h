// Validated configuration of bodies and of the world: the one place that knows every key, its range
// and what it is called in YAML, ROS parameters and dynamic_reconfigure.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "rigid_body_sim/core/constants.h"
#include "rigid_body_sim/core/rod.h"
#include "rigid_body_sim/core/roller.h"

namespace rigid_body_sim {

// A refused value. what() is one line naming the body, the key, the value and what is allowed: control
// characters (a newline in a key, say) are escaped and an overlong value is cut, so that it stays one line.
class ConfigError : public std::runtime_error {
 public:
  ConfigError(const std::string& body, const std::string& key, const std::string& value,
              const std::string& allowed);
  explicit ConfigError(const std::string& message);  // for errors that concern no single key
};

// An interval of allowed values; an open end excludes its bound.
struct Range {
  double min;
  double max;
  bool min_open = false;
  bool max_open = false;
  bool contains(double value) const;  // false for NaN and infinities
  std::string describe() const;       // e.g. "a number in (0, 1e+09]"
};

struct RodConfig {
  RodParams params;
  RodMotion initial;
};

struct RollerConfig {
  RollerParams params;
  RollerInitial initial;
};

// A numeric key of a body: its YAML name, where it lives in the config, and its allowed range.
template <class Config>
struct NumericKey {
  const char* name;
  double& (*field)(Config&);
  Range range;
};

const std::vector<NumericKey<RodConfig>>& rodNumericKeys();
const std::vector<NumericKey<RollerConfig>>& rollerNumericKeys();

// The key named `name`, or null.
template <class Config>
const NumericKey<Config>* findKey(const std::vector<NumericKey<Config>>& keys, const std::string& name) {
  for (const auto& key : keys) {
    if (name == key.name) return &key;
  }
  return nullptr;
}

// Throw ConfigError on the first refused value (ranges, then relations between keys such as
// mu_d <= mu_s, x0 on the slope, inertia_factor matching the shape).
// A rod also needs its contact frequency sqrt(4 k / mass) <= maxContactFrequency(): its sub-stepping
// costs about 10 sub-steps per rad/s and simulated second, and the step count per step must stay an int.
void validate(const std::string& body, const RodConfig& config);
void validate(const std::string& body, const RollerConfig& config);
double maxContactFrequency();  // rad/s

// What `substeps` allows, for messages: "auto or a whole number in [1, 1e+09]".
std::string substepsAllowed();
// A rod's fixed sub-step count must keep each sub-step stable at the world's rate: omega_c dt / N < 2
// (validate(WorldConfig) checks it; the node again for a reconfigured rod). A roller has none.
void validateSubsteps(const std::string& body, const RodConfig& config, double rate);
inline void validateSubsteps(const std::string&, const RollerConfig&, double) {}

struct BodyConfig {
  std::string name;  // also the TF frame and the topic namespace
  std::variant<RodConfig, RollerConfig> config;
};

enum class BodyKind { Rod, Roller };
BodyKind kindOf(const BodyConfig& body);

// True when the initial conditions differ (the body restarts), false when only parameters changed.
bool initialChanged(const RodConfig& a, const RodConfig& b);
bool initialChanged(const RollerConfig& a, const RollerConfig& b);

// The most bodies a world holds, from its config file or spawned while it runs: each brings a thread-safe
// publisher, a reconfigure server and markers to the node, and a CSV file to `simulate`.
constexpr std::size_t kMaxBodies = 1000;

struct WorldConfig {
  double rate = 1000.0;              // physics steps per simulated second
  double publish_rate = 50.0;        // samples per simulated second
  double gravity = kDefaultGravity;  // copied into every body
  std::string world_frame = "world";
  std::vector<BodyConfig> bodies;
};

// The world's keys in a config file, in the order of WorldConfig.
const std::vector<std::string>& worldKeys();

// World-level ranges.
Range rateRange();
Range publishRateRange();
Range gravityRange();

// The longest name of a body or of world_frame: it names topics, services and frames, and lines of text.
inline constexpr std::size_t kMaxNameLength = 64;

// True for a name usable as a ROS graph name component and as a TF frame: [A-Za-z][A-Za-z0-9_]*, at most
// kMaxNameLength characters.
bool isValidName(const std::string& name);

// The fixed frame in which a body's coordinates are measured: <name>_floor (rod) or <name>_slope (roller).
std::string fixedFrameOf(const std::string& name, BodyKind kind);
std::string fixedFrameOf(const BodyConfig& body);

// Checks the world keys, every body, name validity, that every TF frame (world_frame, each body and its
// fixed frame) is distinct, that there are 1 to kMaxBodies bodies, and that publish_rate divides rate. A body
// cannot be named like a world key nor like one of `reserved_names`: the names of the node's private
// namespace, which the bodies share (its options, topics and services; a body named `rate` would shadow the
// world's rate).
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

// Formats a double the way error messages and CSV files show it (shortest round-trip form).
std::string formatNumber(double value);

}  // namespace rigid_body_sim
