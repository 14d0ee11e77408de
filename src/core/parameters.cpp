#include "rigid_body_sim/core/parameters.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <random>
#include <set>

#include "rigid_body_sim/core/constants.h"

namespace rigid_body_sim {

namespace {

// Upper bounds are generous, but finite: an absurd value is far more often a typo than an intent.
constexpr double kMaxMass = 1e9;
constexpr double kMaxSize = 1e6;
constexpr double kMaxSpeed = 1e4;
constexpr double kMaxSpin = 1e6;
constexpr double kMaxAngle = 1e6;
constexpr double kMaxStiffness = 1e12;
constexpr double kMaxFriction = 100.0;
constexpr double kMaxInertiaFactor = 100.0;
// sqrt(4 k / mass) at most 1e8 rad/s: sub-stepping then needs at most 1e9 sub-steps per simulated second
// (and per step at rate 1), about a minute of CPU; far beyond that a run never ends, and the sub-step count
// of a step would overflow.
constexpr double kMaxContactFrequency = 1e8;
// What a message shows of a value or name: the rest of an overlong one is cut.
constexpr std::size_t kMaxShownLength = 80;

// Escapes control characters, so that a message stays one line, and cuts what is longer than max_length.
std::string printable(const std::string& text, std::size_t max_length = std::string::npos) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (out.size() >= max_length) return out + "...";
    const auto ch = static_cast<unsigned char>(text[i]);
    if (ch == '\n') {
      out += "\\n";
    } else if (ch < 0x20 || ch == 0x7f) {
      static const char* hex = "0123456789abcdef";
      out += std::string("\\x") + hex[ch >> 4] + hex[ch & 15];
    } else {
      out += static_cast<char>(ch);
    }
  }
  return out;
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& name : names) out += (out.empty() ? "" : ", ") + name;
  return out;
}

Range positive(double max) { return {0.0, max, true, false}; }
Range closed(double min, double max) { return {min, max, false, false}; }

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

}  // namespace

ConfigError::ConfigError(const std::string& body, const std::string& key, const std::string& value,
                         const std::string& allowed)
    : std::runtime_error("body '" + printable(body, kMaxShownLength) + "', key '" +
                         printable(key, kMaxShownLength) + "': value " + printable(value, kMaxShownLength) +
                         " is not allowed (allowed: " + printable(allowed) + ")") {}

ConfigError::ConfigError(const std::string& message) : std::runtime_error(printable(message)) {}

bool Range::contains(double value) const {
  if (!std::isfinite(value)) return false;
  const bool above_min = min_open ? value > min : value >= min;
  const bool below_max = max_open ? value < max : value <= max;
  return above_min && below_max;
}

std::string Range::describe() const {
  return std::string("a finite number in ") + (min_open ? "(" : "[") + formatNumber(min) + ", " +
         formatNumber(max) + (max_open ? ")" : "]");
}

namespace {

// A number of a body type's description.
template <class Config>
BodyKey<Config> number(const char* name, const char* unit, const char* meaning, KeyChange change,
                       double& (*field)(Config&), Range range, const char* state_field = nullptr) {
  BodyKey<Config> key{name, unit, meaning, change};
  key.field = field;
  key.range = range;
  key.state_field = state_field;
  return key;
}

// A text of a body type's description: an enum's names (`choices`) or what `allowed` says.
template <class Config>
BodyKey<Config> text(const char* name, const char* meaning, KeyChange change,
                     std::string (*write)(const Config&), bool (*read)(Config&, const std::string&),
                     std::vector<std::string> (*choices)(), std::string (*allowed)() = nullptr) {
  BodyKey<Config> key{name, "", meaning, change};
  key.write = write;
  key.read = read;
  key.choices = choices;
  key.allowed_text = allowed;
  return key;
}

std::vector<std::string> integratorNames() {
  return {toString(Integrator::EulerCromer), toString(Integrator::VelocityVerlet), toString(Integrator::Rk4)};
}

std::vector<std::string> shapeNames() {
  std::vector<std::string> names;
  for (const Shape shape : namedShapes()) names.push_back(toString(shape));
  names.push_back(toString(Shape::Custom));
  return names;
}
std::string seedAllowed() { return "a whole number in [0, 2^53), only when theta0 is not given"; }

// A seed in [0, 2^53): a double holds every such whole number exactly.
bool readSeed(RodConfig& config, const std::string& text) {
  char* end = nullptr;
  const double seed = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size()) return false;
  if (!(seed >= 0 && seed < 9.007199254740992e15 && seed == std::floor(seed))) return false;
  config.initial.theta = theta0FromSeed(static_cast<unsigned long long>(seed));
  return true;
}

bool given(const std::vector<std::string>& keys, const char* name) {
  return std::find(keys.begin(), keys.end(), name) != keys.end();
}

void completeRod(const std::string& body, const std::vector<std::string>& keys, RodConfig&) {
  if (given(keys, "seed") && given(keys, "theta0")) {
    throw ConfigError(body, "seed", "(with theta0)", "only when theta0 is not given");
  }
}

// shape names a body with a known c (read first, it sets c); inertia_factor alone means shape custom.
void completeRoller(const std::string& body, const std::vector<std::string>& keys, RollerConfig& config) {
  const bool has_factor = given(keys, "inertia_factor");
  if (has_factor && !given(keys, "shape")) config.params.shape = Shape::Custom;
  if (config.params.shape == Shape::Custom && !has_factor) {
    throw ConfigError(body, "shape", "'custom'", "custom only with inertia_factor");
  }
}

}  // namespace

const BodyType<RodConfig>& rodType() {
  using C = RodConfig;
  constexpr auto apply = KeyChange::Apply;
  constexpr auto restart = KeyChange::Restart;
  static const BodyType<RodConfig> type{
      "rod",
      {
          number<C>(
              "length", "m", "length", apply, [](C& c) -> double& { return c.params.length; },
              positive(kMaxSize)),
          number<C>(
              "mass", "kg", "mass", apply, [](C& c) -> double& { return c.params.mass; }, positive(kMaxMass)),
          number<C>(
              "k", "N/m", "floor spring constant per end", apply, [](C& c) -> double& { return c.params.k; },
              positive(kMaxStiffness)),
          number<C>(
              "floor_length", "m", "floor length from x = 0, 0 = unbounded", apply,
              [](C& c) -> double& { return c.params.floor_length; }, closed(0, kMaxSize)),
          number<C>(
              "floor_mu", "", "Coulomb friction of the floor at the rod's ends, 0 = frictionless", apply,
              [](C& c) -> double& { return c.params.floor_mu; }, closed(0, kMaxFriction)),
          number<C>(
              "x0", "m", "initial centre x", restart, [](C& c) -> double& { return c.initial.x; },
              closed(-kMaxSize, kMaxSize), "x"),
          // A centre under the floor is refused: a rod starts at or above it (it may lie on it, y0 = 0).
          number<C>(
              "y0", "m", "initial centre height", restart, [](C& c) -> double& { return c.initial.y; },
              closed(0, kMaxSize), "y"),
          number<C>(
              "vx0", "m/s", "initial velocity x", restart, [](C& c) -> double& { return c.initial.vx; },
              closed(-kMaxSpeed, kMaxSpeed), "vx"),
          number<C>(
              "vy0", "m/s", "initial velocity y", restart, [](C& c) -> double& { return c.initial.vy; },
              closed(-kMaxSpeed, kMaxSpeed), "vy"),
          number<C>(
              "theta0", "rad", "initial angle from +x", restart,
              [](C& c) -> double& { return c.initial.theta; }, closed(-kMaxAngle, kMaxAngle), "theta"),
          number<C>(
              "omega0", "rad/s", "initial angular velocity", restart,
              [](C& c) -> double& { return c.initial.omega; }, closed(-kMaxSpin, kMaxSpin), "omega"),
          text<C>(
              "integrator", "integration scheme", apply,
              [](const C& c) { return toString(c.params.integrator); },
              [](C& c, const std::string& name) {
                const auto integrator = integratorFromString(name);
                if (integrator) c.params.integrator = *integrator;
                return integrator.has_value();
              },
              integratorNames),
          [] {
            auto key = text<C>(
                "substeps",
                "sub-steps per step: auto (split only when omega_c dt > 0.1) or a whole number N >= 1 with "
                "omega_c dt / N < 2 (1: the text's scheme)",
                apply, [](const C& c) { return substepsToString(c.params.substeps); },
                [](C& c, const std::string& value) {
                  const auto substeps = substepsFromString(value);
                  if (substeps) c.params.substeps = *substeps;
                  return substeps.has_value();
                },
                nullptr, substepsAllowed);
            key.counts = true;
            return key;
          }(),
          text<C>("seed", "draws theta0 = 2 pi u, u from std::mt19937_64(seed), instead of theta0", restart,
                  nullptr, readSeed, nullptr, seedAllowed),
      },
      completeRod};
  return type;
}

const BodyType<RollerConfig>& rollerType() {
  using C = RollerConfig;
  constexpr auto apply = KeyChange::Apply;
  constexpr auto restart = KeyChange::Restart;
  static const BodyType<RollerConfig> type{
      "roller",
      {
          // Before inertia_factor: a named shape sets c, which a given inertia_factor then overrides (and
          // validation refuses unless it is the shape's).
          text<C>(
              "shape", "shape (sets c unless custom)", apply,
              [](const C& c) { return toString(c.params.shape); },
              [](C& c, const std::string& name) {
                if (name == toString(Shape::Custom)) {
                  c.params.shape = Shape::Custom;
                  return true;
                }
                const auto shape = shapeFromString(name);
                if (!shape) return false;
                c.params.shape = *shape;
                c.params.inertia_factor = inertiaFactorOf(*shape);
                return true;
              },
              shapeNames),
          number<C>(
              "inertia_factor", "", "c = I / (M R^2), used with shape custom", apply,
              [](C& c) -> double& { return c.params.inertia_factor; }, positive(kMaxInertiaFactor)),
          number<C>(
              "radius", "m", "radius", apply, [](C& c) -> double& { return c.params.radius; },
              positive(kMaxSize)),
          number<C>(
              "mass", "kg", "mass", apply, [](C& c) -> double& { return c.params.mass; }, positive(kMaxMass)),
          number<C>("incline_angle", "rad", "slope angle", apply,
                    [](C& c) -> double& { return c.params.incline_angle; }, {0.0, kPi / 2, false, true}),
          number<C>(
              "incline_length", "m", "slope length", apply,
              [](C& c) -> double& { return c.params.incline_length; }, positive(kMaxSize)),
          number<C>(
              "mu_s", "", "static friction coefficient", apply, [](C& c) -> double& { return c.params.mu_s; },
              closed(0, kMaxFriction)),
          number<C>(
              "mu_d", "", "kinetic friction coefficient, <= mu_s", apply,
              [](C& c) -> double& { return c.params.mu_d; }, closed(0, kMaxFriction)),
          number<C>(
              "x0", "m", "initial position along the slope, <= incline_length", restart,
              [](C& c) -> double& { return c.initial.x0; }, closed(0, kMaxSize), "x"),
          number<C>(
              "v0", "m/s", "initial velocity along the slope", restart,
              [](C& c) -> double& { return c.initial.v0; }, closed(-kMaxSpeed, kMaxSpeed), "v"),
          number<C>(
              "theta0", "rad", "initial rotation", restart, [](C& c) -> double& { return c.initial.theta0; },
              closed(-kMaxAngle, kMaxAngle), "theta"),
          number<C>(
              "omega0", "rad/s", "initial angular velocity", restart,
              [](C& c) -> double& { return c.initial.omega0; }, closed(-kMaxSpin, kMaxSpin), "omega"),
      },
      completeRoller};
  return type;
}

std::string oneOf(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    out += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  }
  return out;
}

double theta0FromSeed(unsigned long long seed) {
  std::mt19937_64 generator(seed);
  const double unit = static_cast<double>(generator() >> 11) * 0x1.0p-53;
  return 2.0 * kPi * unit;
}

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

template void setKeyText(const std::string&, const BodyKey<RodConfig>&, const std::string&, RodConfig&);
template void setKeyText(const std::string&, const BodyKey<RollerConfig>&, const std::string&, RollerConfig&);

// A quantity derived from the keys (an inertia, a frequency, an energy at the start) that a step divides by
// or carries: refused unless finite and, where asked, a normal positive double (an underflow to 0 or into the
// subnormals would make a step divide by (nearly) nothing, and the state non-finite).
void checkDerived(const std::string& body, const std::string& keys, const std::string& quantity, double value,
                  bool positive) {
  const bool good = positive ? std::isnormal(value) && value > 0.0 : std::isfinite(value);
  if (!good) {
    throw ConfigError(body, keys, quantity + " = " + formatNumber(value),
                      positive ? "values whose " + quantity + " is a finite positive number (at least " +
                                     formatNumber(std::numeric_limits<double>::min()) + ")"
                               : "values whose " + quantity + " is finite");
  }
}

void checkDerived(const std::string& body, const RodConfig& config) {
  const Rod rod(config.params, config.initial);
  checkDerived(body, "mass, length", "moment of inertia M L^2 / 12", rod.momentOfInertia(), true);
  checkDerived(body, "k, mass", "omega_c = sqrt(4 k / mass)", rod.contactFrequency(), true);
  checkDerived(body, "mass, length, k and the initial conditions", "energy at the start", rod.energy(),
               false);
}

void checkDerived(const std::string& body, const RollerConfig& config) {
  const RollerParams& p = config.params;
  const double c_m_r = p.inertia_factor * p.mass * p.radius;  // friction / (c M R) is the spin's rate
  checkDerived(body, "inertia_factor, mass, radius", "c M R", c_m_r, true);
  checkDerived(body, "inertia_factor, mass, radius", "moment of inertia c M R^2", c_m_r * p.radius, true);
  const Roller roller(p, config.initial);
  checkDerived(body, "mass, radius and the initial conditions", "energy at the start", roller.energy(),
               false);
}

void validate(const std::string& body, const RodConfig& config) {
  checkRanges(body, config);
  const RodParams& p = config.params;
  const double x0 = config.initial.x;
  if (p.floor_length > 0.0 && !(x0 >= 0.0 && x0 <= p.floor_length)) {
    throw ConfigError(body, "x0", formatNumber(x0),
                      "a position on the floor, in [0, floor_length = " + formatNumber(p.floor_length) + "]");
  }
  if (!gravityRange().contains(p.gravity)) {
    throw ConfigError(body, "gravity", formatNumber(p.gravity), gravityRange().describe());
  }
  if (p.substeps != kAutoSubsteps && !(p.substeps >= 1 && p.substeps <= kMaxSubsteps)) {
    throw ConfigError(body, "substeps", std::to_string(p.substeps), substepsAllowed());
  }
  // sqrt(4 k / M) <= w  <=>  k <= w^2 M / 4
  const double max_k = kMaxContactFrequency * kMaxContactFrequency * p.mass / 4.0;
  if (p.k > max_k) {
    throw ConfigError(body, "k", formatNumber(p.k),
                      "a finite number in (0, " + formatNumber(max_k) +
                          "] for mass = " + formatNumber(p.mass) + ": sqrt(4 k / mass) at most " +
                          formatNumber(kMaxContactFrequency) + " rad/s");
  }
  checkDerived(body, config);
}

double maxContactFrequency() { return kMaxContactFrequency; }

std::string substepsAllowed() { return "auto or a whole number in [1, " + formatNumber(kMaxSubsteps) + "]"; }

void validateSubsteps(const std::string& body, const RodConfig& config, double rate) {
  const int n = config.params.substeps;
  if (n == kAutoSubsteps) return;
  const double ratio = Rod(config.params, config.initial).contactFrequency() / rate;  // omega_c dt
  if (ratio / n < 2.0) return;
  const double smallest = std::floor(ratio / 2.0) + 1.0;
  throw ConfigError(body, "substeps", std::to_string(n),
                    "auto or a whole number N >= " + formatNumber(smallest) +
                        ": a sub-step is stable only while omega_c dt / N < 2, and here omega_c dt = " +
                        formatNumber(ratio) + " with omega_c = sqrt(4 k / mass), k = " +
                        formatNumber(config.params.k) + ", mass = " + formatNumber(config.params.mass) +
                        ", dt = 1 / rate = " + formatNumber(1.0 / rate) + " s");
}

void validate(const std::string& body, const RollerConfig& config) {
  checkRanges(body, config);
  const RollerParams& p = config.params;
  if (!gravityRange().contains(p.gravity)) {
    throw ConfigError(body, "gravity", formatNumber(p.gravity), gravityRange().describe());
  }
  // Kinetic friction above static friction has no consistent Coulomb law at u = 0.
  if (p.mu_d > p.mu_s) {
    throw ConfigError(body, "mu_d", formatNumber(p.mu_d),
                      "a finite number in [0, mu_s = " + formatNumber(p.mu_s) + "]");
  }
  if (config.initial.x0 > p.incline_length) {
    throw ConfigError(
        body, "x0", formatNumber(config.initial.x0),
        "a position on the slope, in [0, incline_length = " + formatNumber(p.incline_length) + "]");
  }
  if (p.shape != Shape::Custom && p.inertia_factor != inertiaFactorOf(p.shape)) {
    throw ConfigError(body, "inertia_factor", formatNumber(p.inertia_factor),
                      "only with shape custom, or " + formatNumber(inertiaFactorOf(p.shape)) + " for shape " +
                          toString(p.shape));
  }
  checkDerived(body, config);
}

Range rateRange() { return {1.0, 1e6, false, false}; }
Range publishRateRange() { return {0.0, 1e6, true, false}; }
Range gravityRange() { return {0.0, 1e3, false, false}; }

bool isValidName(const std::string& name) {
  if (name.empty() || name.size() > kMaxNameLength || !std::isalpha(static_cast<unsigned char>(name[0])))
    return false;
  for (const char ch : name) {
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '_') return false;
  }
  return true;
}

bool dividesRate(double rate, double divisor) {
  if (!(divisor > 0) || !std::isfinite(rate) || !std::isfinite(divisor)) return false;
  const double ratio = rate / divisor;
  return ratio >= 1.0 - 1e-9 && std::abs(ratio - std::round(ratio)) <= 1e-9 * ratio;
}

BodyKind kindOf(const BodyConfig& body) {
  return std::holds_alternative<RodConfig>(body.config) ? BodyKind::Rod : BodyKind::Roller;
}

std::string fixedFrameOf(const std::string& name, BodyKind kind) {
  return name + (kind == BodyKind::Rod ? "_floor" : "_slope");
}

std::string fixedFrameOf(const BodyConfig& body) { return fixedFrameOf(body.name, kindOf(body)); }

std::string groundFrameOf(const std::string& name) { return name + "_ground"; }

const std::vector<std::string>& worldKeys() {
  static const std::vector<std::string> keys = {"rate",        "publish_rate", "gravity",
                                                "world_frame", "race",         "bodies"};
  return keys;
}

void validate(const WorldConfig& config, const std::vector<std::string>& reserved_names) {
  const std::string world = "(world)";
  if (!rateRange().contains(config.rate)) {
    throw ConfigError(world, "rate", formatNumber(config.rate), rateRange().describe());
  }
  if (!publishRateRange().contains(config.publish_rate) || !dividesRate(config.rate, config.publish_rate)) {
    throw ConfigError(world, "publish_rate", formatNumber(config.publish_rate),
                      "a divisor of rate = " + formatNumber(config.rate) + " (rate / publish_rate whole)");
  }
  if (!gravityRange().contains(config.gravity)) {
    throw ConfigError(world, "gravity", formatNumber(config.gravity), gravityRange().describe());
  }
  if (!isValidName(config.world_frame)) {
    throw ConfigError(world, "world_frame", "'" + config.world_frame + "'",
                      "a name of letters, digits and _ starting with a letter, at most " +
                          std::to_string(kMaxNameLength) + " characters");
  }
  if (config.bodies.empty()) {
    throw ConfigError(world, "bodies", "(none)", "a map of at least one body");
  }
  if (config.bodies.size() > kMaxBodies) {
    throw ConfigError(world, "bodies", std::to_string(config.bodies.size()) + " bodies",
                      "at most " + std::to_string(kMaxBodies) + " bodies");
  }
  std::set<std::string> frames{config.world_frame};
  std::vector<std::string> reserved = worldKeys();
  reserved.insert(reserved.end(), reserved_names.begin(), reserved_names.end());
  for (const auto& body : config.bodies) {
    if (!isValidName(body.name)) {
      throw ConfigError(world, "bodies", "'" + body.name + "'",
                        "body names of letters, digits and _ starting with a letter, at most " +
                            std::to_string(kMaxNameLength) + " characters");
    }
    if (std::find(reserved.begin(), reserved.end(), body.name) != reserved.end()) {
      throw ConfigError(
          world, "bodies", "'" + body.name + "'",
          "a name other than the node's own keys, topics and services (" + joined(reserved) + ")");
    }
    // Each body brings two TF frames: its own and its fixed frame (<name>_floor or <name>_slope); a rod
    // a third, its ground frame (on an unbounded floor, which a reconfigure may make it).
    const bool rod = kindOf(body) == BodyKind::Rod;
    if (!frames.insert(body.name).second || !frames.insert(fixedFrameOf(body)).second ||
        (rod && !frames.insert(groundFrameOf(body.name)).second)) {
      throw ConfigError(world, "bodies", "'" + body.name + "'",
                        "names whose TF frames (<name>, <name>_floor or <name>_slope, a rod's <name>_ground) "
                        "differ from each other and from world_frame");
    }
    std::visit(
        [&](const auto& body_config) {
          validate(body.name, body_config);
          validateSubsteps(body.name, body_config, config.rate);
        },
        body.config);
  }
}

std::vector<std::string> slowRunWarnings(const WorldConfig& config) {
  std::vector<std::string> warnings;
  for (const auto& body : config.bodies) {
    const auto* rod = std::get_if<RodConfig>(&body.config);
    if (!rod) continue;  // a roller's step is closed-form: never sub-stepped
    const int per_step = Rod(rod->params, rod->initial).substepsFor(1.0 / config.rate);
    const double per_second = per_step * config.rate;
    if (per_second > kSlowSubstepsPerSecond) {
      warnings.push_back("body '" + body.name + "': k = " + formatNumber(rod->params.k) + " with mass = " +
                         formatNumber(rod->params.mass) + " needs " + std::to_string(per_step) +
                         " sub-steps per step at rate " + formatNumber(config.rate) + " (" +
                         formatNumber(per_second) + " per simulated second): the run will be slow");
    }
  }
  return warnings;
}

std::vector<std::string> autoSubstepNotes(const WorldConfig& config) {
  std::vector<std::string> notes;
  for (const auto& body : config.bodies) {
    const auto* rod = std::get_if<RodConfig>(&body.config);
    if (!rod || rod->params.substeps != kAutoSubsteps) continue;
    const Rod model(rod->params, rod->initial);
    const int n = model.autoSubstepsFor(1.0 / config.rate);
    if (n == 1) continue;
    notes.push_back(
        "body '" + body.name + "': substeps auto splits each step into " + std::to_string(n) +
        " sub-steps, as omega_c dt = " + formatNumber(model.contactFrequency() / config.rate) +
        " (omega_c = sqrt(4 k / mass) at k = " + formatNumber(rod->params.k) +
        ", mass = " + formatNumber(rod->params.mass) + ", rate = " + formatNumber(config.rate) +
        ") is above " + formatNumber(2.0 * Rod::kSubstepFraction) +
        "; substeps: N fixes the count instead (stable for N > omega_c dt / 2; 1 is the text's scheme)");
  }
  return notes;
}

}  // namespace rigid_body_sim
