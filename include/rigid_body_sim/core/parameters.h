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

// How a key's change applies to a running body: at the next step, or by restarting the body from its
// initial conditions (the key is one of them). The levels of the reconfigure servers' .cfg files.
enum class KeyChange { Apply = 0, Restart = 1 };

// One key of a body type: its name, unit, meaning, how it is read and written and whether a change restarts
// the body. A number lives in a double of the config (`field`) and is written in its shortest round-trip
// form; a text (an enum name, `auto` or a count) is written by `write` and read by `read`. The loader, the
// writer
// (~get_config, the command log), the reconfigure conversion, the guard's report, the sweep's keys, the docs'
// tables and the round-trip tests all walk these tables: a key added to one is added everywhere.
template <class Config>
struct BodyKey {
  const char* name;
  const char* unit;     // SI unit of a number ("" for a pure number or a text)
  const char* meaning;  // one line: the docs' tables and the .cfg's descriptions
  KeyChange change;
  // A number: where it lives and its allowed range (null for a text).
  double& (*field)(Config&) = nullptr;
  Range range{};
  // A text: its value as written (null: never written, as `seed`, which writes theta0), its reader (false:
  // refused, the config as it was), and what it allows: the names of `choices` (an enum's), or allowed_text.
  std::string (*write)(const Config&) = nullptr;
  bool (*read)(Config&, const std::string&) = nullptr;
  std::vector<std::string> (*choices)() = nullptr;
  std::string (*allowed_text)() = nullptr;
  // The state field whose initial value the key is (x0: "x"): a set_state value takes this key's range.
  const char* state_field = nullptr;
  // A text that takes whole numbers too (substeps): a sweep varies it as numbers.
  bool counts = false;

  bool isNumber() const { return field != nullptr; }
  bool written() const { return field != nullptr || write != nullptr; }
  double number(const Config& config) const { return field(const_cast<Config&>(config)); }
  // As a config file writes it; a key that is never written gives "".
  std::string text(const Config& config) const;
  // What it allows, for messages and the docs.
  std::string allowed() const;
};

// The description of a body type: its `type` name in a config file and its keys in the order files list them.
// `complete` runs after a config file's keys are read, with the names of those given: what depends on which
// keys a file gave (a roller's inertia_factor alone means shape custom; a rod's seed excludes theta0).
template <class Config>
struct BodyType {
  const char* type;
  std::vector<BodyKey<Config>> keys;
  void (*complete)(const std::string& body, const std::vector<std::string>& given, Config& config);
};

const BodyType<RodConfig>& rodType();
const BodyType<RollerConfig>& rollerType();
// The type of a config: bodyType<RodConfig>() is rodType().
template <class Config>
const BodyType<Config>& bodyType();
template <>
inline const BodyType<RodConfig>& bodyType<RodConfig>() {
  return rodType();
}
template <>
inline const BodyType<RollerConfig>& bodyType<RollerConfig>() {
  return rollerType();
}

// The key named `name`, or null.
template <class Config>
const BodyKey<Config>* findKey(const std::vector<BodyKey<Config>>& keys, const std::string& name) {
  for (const auto& key : keys) {
    if (name == key.name) return &key;
  }
  return nullptr;
}

// The key whose initial value state field `field` takes (x: x0), or null.
template <class Config>
const BodyKey<Config>* keyOfStateField(const std::string& field) {
  for (const auto& key : bodyType<Config>().keys) {
    if (key.state_field && field == key.state_field) return &key;
  }
  return nullptr;
}

// Sets `key` of `config` from its text as a file writes it (a number: digits as formatNumber writes them, or
// any form strtod reads); throws ConfigError naming the body, the key, the value and what is allowed.
template <class Config>
void setKeyText(const std::string& body, const BodyKey<Config>& key, const std::string& text, Config& config);

// The theta0 drawn for a rod from `seed` when theta0 is not given: 2 pi u, u uniform in [0, 1) from
// the first output of std::mt19937_64(seed) (portable, unlike std::uniform_real_distribution).
double theta0FromSeed(unsigned long long seed);

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
  // A race: the rollers start together, each stops at the end of its slope, and all start a new lap together
  // once every one has finished and the results have stood 2 s (World::step); false: each restarts alone at
  // the end of its slope.
  bool race = false;
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
// A rod's frame under it on an unbounded floor: <name>_ground.
std::string groundFrameOf(const std::string& name);

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
// A double with `decimals` digits after the point, for people to read (a panel, a chart's ticks): never
// "-0.000", which reads as a sign that is not there; a value that rounds to zero is "0.000".
std::string formatFixed(double value, int decimals);

// "a, b or c".
std::string oneOf(const std::vector<std::string>& names);

template <class Config>
std::string BodyKey<Config>::allowed() const {
  if (isNumber()) return range.describe();
  return choices ? oneOf(choices()) : allowed_text();
}

template <class Config>
std::string BodyKey<Config>::text(const Config& config) const {
  if (isNumber()) return formatNumber(number(config));
  return write ? write(config) : "";
}

}  // namespace rigid_body_sim
