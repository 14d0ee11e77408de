// What the body types' own files (src/core/types/) describe and check their keys with: the bounds of their
// ranges and the builders of a description's rows. Internal to the core library.
#pragma once

#include <algorithm>
#include <initializer_list>
#include <string>
#include <vector>

#include "rigid_body_sim/core/body_key.h"
#include "rigid_body_sim/core/body_types.h"
#include "rigid_body_sim/core/constants.h"

namespace rigid_body_sim::keys {

// Upper bounds are generous, but finite: an absurd value is far more often a typo than an intent.
constexpr double kMaxMass = 1e9;
constexpr double kMaxSize = 1e6;
constexpr double kMaxSpeed = 1e4;
constexpr double kMaxSpin = 1e6;
constexpr double kMaxAngle = 1e6;
constexpr double kMaxStiffness = 1e12;
constexpr double kMaxFriction = 100.0;
constexpr double kMaxInertiaFactor = 100.0;

inline Range positive(double max) { return {0.0, max, true, false}; }
inline Range closed(double min, double max) { return {min, max, false, false}; }

// A number of a body type's description.
template <class Config>
inline BodyKey<Config> number(const char* name, const char* unit, const char* meaning, KeyChange change,
                              double& (*field)(Config&), Range range, const char* state_field = nullptr) {
  BodyKey<Config> key{name, unit, meaning, change};
  key.field = field;
  key.range = range;
  key.state_field = state_field;
  return key;
}

// A text of a body type's description: an enum's names (`choices`) or what `allowed` says.
template <class Config>
inline BodyKey<Config> text(const char* name, const char* meaning, KeyChange change,
                            std::string (*write)(const Config&), bool (*read)(Config&, const std::string&),
                            std::vector<std::string> (*choices)(), std::string (*allowed)() = nullptr) {
  BodyKey<Config> key{name, "", meaning, change};
  key.write = write;
  key.read = read;
  key.choices = choices;
  key.allowed_text = allowed;
  return key;
}

// The key, marked as one a lesson page may change.
template <class Config>
BodyKey<Config> lesson(BodyKey<Config> key) {
  key.lesson = true;
  return key;
}

inline bool given(const std::vector<std::string>& keys, const char* name) {
  return std::find(keys.begin(), keys.end(), name) != keys.end();
}

// Every number of the config within its row's range; throws ConfigError naming the first that is not.
template <class Config>
void checkRanges(const std::string& body, const Config& config) {
  for (const auto& key : bodyType<Config>().keys) {
    if (!key.isNumber()) continue;
    const double value = key.number(config);
    if (!key.range.contains(value)) {
      throw ConfigError(body, key.name, formatNumber(value), key.range.describe());
    }
  }
}

// A quantity derived from the keys (an inertia, a frequency, an energy at the start) that a step divides by
// or carries: refused unless finite and, where asked, a normal positive double (an underflow to 0 or into the
// subnormals would make a step divide by (nearly) nothing, and the state non-finite).
void checkDerived(const std::string& body, const std::string& keys, const std::string& quantity, double value,
                  bool positive);

// Runs of keys, one after the other.
template <class C>
std::vector<BodyKey<C>> concat(std::initializer_list<std::vector<BodyKey<C>>> runs) {
  std::vector<BodyKey<C>> keys;
  for (const auto& run : runs) keys.insert(keys.end(), run.begin(), run.end());
  return keys;
}

// The keys every body on an incline has, in this order: mass, incline_angle, incline_length, mu_s, mu_d,
// x0 and v0 (Config: its params and initial conditions name them so).
template <class C>
const std::vector<BodyKey<C>>& inclineKeys() {
  constexpr auto apply = KeyChange::Apply;
  constexpr auto restart = KeyChange::Restart;
  static const std::vector<BodyKey<C>> keys{
      number<C>(
          "mass", "kg", "mass", apply, [](C& c) -> double& { return c.params.mass; }, positive(kMaxMass)),
      lesson(number<C>("incline_angle", "rad", "slope angle", apply,
                       [](C& c) -> double& { return c.params.incline_angle; }, {0.0, kPi / 2, false, true})),
      number<C>(
          "incline_length", "m", "slope length", apply,
          [](C& c) -> double& { return c.params.incline_length; }, positive(kMaxSize)),
      lesson(number<C>(
          "mu_s", "", "static friction coefficient", apply, [](C& c) -> double& { return c.params.mu_s; },
          closed(0, kMaxFriction))),
      lesson(number<C>(
          "mu_d", "", "kinetic friction coefficient, <= mu_s", apply,
          [](C& c) -> double& { return c.params.mu_d; }, closed(0, kMaxFriction))),
      lesson(number<C>(
          "x0", "m", "initial position along the slope, <= incline_length", restart,
          [](C& c) -> double& { return c.initial.x0; }, closed(0, kMaxSize), "x")),
      lesson(number<C>(
          "v0", "m/s", "initial velocity along the slope", restart,
          [](C& c) -> double& { return c.initial.v0; }, closed(-kMaxSpeed, kMaxSpeed), "v")),
  };
  return keys;
}

// The relations every body on an incline keeps: mu_d <= mu_s (kinetic friction above static friction has no
// consistent Coulomb law at rest), and a position `key` on its slope, in [0, incline_length]. Throw
// ConfigError.
void checkFriction(const std::string& body, double mu_s, double mu_d);
void checkOnSlope(const std::string& body, const char* key, double x, double incline_length);

}  // namespace rigid_body_sim::keys
