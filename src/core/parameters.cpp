#include "rigid_body_sim/core/parameters.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
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
void checkRanges(const std::string& body, const Config& config, const std::vector<NumericKey<Config>>& keys) {
  auto& mutable_config = const_cast<Config&>(config);  // NumericKey fields are shared with the loader
  for (const auto& key : keys) {
    const double value = key.field(mutable_config);
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

const std::vector<NumericKey<RodConfig>>& rodNumericKeys() {
  static const std::vector<NumericKey<RodConfig>> keys = {
      {"length", [](RodConfig& c) -> double& { return c.params.length; }, positive(kMaxSize)},
      {"mass", [](RodConfig& c) -> double& { return c.params.mass; }, positive(kMaxMass)},
      {"k", [](RodConfig& c) -> double& { return c.params.k; }, positive(kMaxStiffness)},
      {"floor_length", [](RodConfig& c) -> double& { return c.params.floor_length; }, closed(0, kMaxSize)},
      {"x0", [](RodConfig& c) -> double& { return c.initial.x; }, closed(-kMaxSize, kMaxSize)},
      // A centre under the floor is refused: a rod starts at or above it (it may lie on it, y0 = 0).
      {"y0", [](RodConfig& c) -> double& { return c.initial.y; }, closed(0, kMaxSize)},
      {"vx0", [](RodConfig& c) -> double& { return c.initial.vx; }, closed(-kMaxSpeed, kMaxSpeed)},
      {"vy0", [](RodConfig& c) -> double& { return c.initial.vy; }, closed(-kMaxSpeed, kMaxSpeed)},
      {"theta0", [](RodConfig& c) -> double& { return c.initial.theta; }, closed(-kMaxAngle, kMaxAngle)},
      {"omega0", [](RodConfig& c) -> double& { return c.initial.omega; }, closed(-kMaxSpin, kMaxSpin)},
  };
  return keys;
}

const std::vector<NumericKey<RollerConfig>>& rollerNumericKeys() {
  static const std::vector<NumericKey<RollerConfig>> keys = {
      {"radius", [](RollerConfig& c) -> double& { return c.params.radius; }, positive(kMaxSize)},
      {"mass", [](RollerConfig& c) -> double& { return c.params.mass; }, positive(kMaxMass)},
      {"inertia_factor", [](RollerConfig& c) -> double& { return c.params.inertia_factor; },
       positive(kMaxInertiaFactor)},
      {"incline_angle",
       [](RollerConfig& c) -> double& { return c.params.incline_angle; },
       {0.0, kPi / 2, false, true}},
      {"incline_length", [](RollerConfig& c) -> double& { return c.params.incline_length; },
       positive(kMaxSize)},
      {"mu_s", [](RollerConfig& c) -> double& { return c.params.mu_s; }, closed(0, kMaxFriction)},
      {"mu_d", [](RollerConfig& c) -> double& { return c.params.mu_d; }, closed(0, kMaxFriction)},
      {"x0", [](RollerConfig& c) -> double& { return c.initial.x0; }, closed(0, kMaxSize)},
      {"v0", [](RollerConfig& c) -> double& { return c.initial.v0; }, closed(-kMaxSpeed, kMaxSpeed)},
      {"theta0", [](RollerConfig& c) -> double& { return c.initial.theta0; }, closed(-kMaxAngle, kMaxAngle)},
      {"omega0", [](RollerConfig& c) -> double& { return c.initial.omega0; }, closed(-kMaxSpin, kMaxSpin)},
  };
  return keys;
}

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
  checkRanges(body, config, rodNumericKeys());
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
  checkRanges(body, config, rollerNumericKeys());
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

bool initialChanged(const RodConfig& a, const RodConfig& b) {
  const RodMotion& p = a.initial;
  const RodMotion& q = b.initial;
  return p.x != q.x || p.y != q.y || p.theta != q.theta || p.vx != q.vx || p.vy != q.vy || p.omega != q.omega;
}

bool initialChanged(const RollerConfig& a, const RollerConfig& b) {
  const RollerInitial& p = a.initial;
  const RollerInitial& q = b.initial;
  return p.x0 != q.x0 || p.v0 != q.v0 || p.theta0 != q.theta0 || p.omega0 != q.omega0;
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

const std::vector<std::string>& worldKeys() {
  static const std::vector<std::string> keys = {"rate", "publish_rate", "gravity", "world_frame", "bodies"};
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
    // Each body brings two TF frames: its own and its fixed frame (<name>_floor or <name>_slope).
    if (!frames.insert(body.name).second || !frames.insert(fixedFrameOf(body)).second) {
      throw ConfigError(world, "bodies", "'" + body.name + "'",
                        "names whose TF frames (<name>, <name>_floor or <name>_slope) differ from each "
                        "other and from world_frame");
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
