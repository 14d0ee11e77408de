// A body type's description, key by key, and the errors and number forms every key shares: what each body
// type's own files (core/types/) describe their keys with.
#pragma once

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

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
  // A key a lesson page may change (the slope, friction, the floor's spring, the initial conditions).
  bool lesson = false;

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

// The key named `name`, or null.
template <class Config>
const BodyKey<Config>* findKey(const std::vector<BodyKey<Config>>& keys, const std::string& name) {
  for (const auto& key : keys) {
    if (name == key.name) return &key;
  }
  return nullptr;
}

// Sets `key` of `config` from its text as a file writes it (a number: digits as formatNumber writes them, or
// any form strtod reads); throws ConfigError naming the body, the key, the value and what is allowed.
template <class Config>
void setKeyText(const std::string& body, const BodyKey<Config>& key, const std::string& text,
                Config& config) {
  if (key.isNumber()) {
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size()) {
      throw ConfigError(body, key.name, "'" + text + "'", key.allowed());
    }
    key.field(config) = value;  // its range is validation's
    return;
  }
  Config changed = config;
  if (!key.read || !key.read(changed, text))
    throw ConfigError(body, key.name, "'" + text + "'", key.allowed());
  config = changed;
}

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

// The column a sweep writes for a body after its final state and energy drift: the rod's bounces, or the
// instant friction first took hold (a roller's slip_to_roll, a block's stop).
struct SweepColumn {
  // Bounces: the run summary's count of contacts begun (Type::touchesFloor); FirstEvent: the instant of the
  // first event of kind `event` (one of the type's kEventKinds), empty when none happened.
  enum class Of { Bounces, FirstEvent };
  const char* name;
  Of of;
  const char* event;  // for FirstEvent
  const char* label;  // for a plot's axis: "slip-to-roll time"
  const char* unit;   // "s", "" for a count
};

// The column a sweep writes for every body: its energy at the end less at the start.
inline constexpr const char* kEnergyDriftColumn = "energy_drift";

}  // namespace rigid_body_sim
