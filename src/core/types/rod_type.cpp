// The rod's description (every key once), its validation and its notes on sub-stepping.
#include "rigid_body_sim/core/types/rod_type.h"

#include <cmath>
#include <cstdlib>
#include <random>

#include "key_builders.h"
#include "rigid_body_sim/core/names.h"
#include "rigid_body_sim/core/parameters.h"
#include "rigid_body_sim/core/rod_dynamics.h"

namespace rigid_body_sim {

using namespace keys;  // NOLINT: the builders of a description's rows

namespace {

// sqrt(4 k / mass) at most 1e8 rad/s: sub-stepping then needs at most 1e9 sub-steps per simulated second
// (and per step at rate 1), about a minute of CPU; far beyond that a run never ends, and the sub-step count
// of a step would overflow.
constexpr double kMaxContactFrequency = 1e8;

std::vector<std::string> integratorNames() {
  return {toString(Integrator::EulerCromer), toString(Integrator::VelocityVerlet), toString(Integrator::Rk4)};
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

void completeRod(const std::string& body, const std::vector<std::string>& keys, RodConfig&) {
  if (given(keys, "seed") && given(keys, "theta0")) {
    throw ConfigError(body, "seed", "(with theta0)", "only when theta0 is not given");
  }
}

}  // namespace

const BodyType<RodConfig>& RodType::description() {
  using C = RodConfig;
  constexpr auto apply = KeyChange::Apply;
  constexpr auto restart = KeyChange::Restart;
  static const BodyType<RodConfig> type{
      RodType::kName,
      {
          number<C>(
              "length", "m", "length", apply, [](C& c) -> double& { return c.params.length; },
              positive(kMaxSize)),
          number<C>(
              "mass", "kg", "mass", apply, [](C& c) -> double& { return c.params.mass; }, positive(kMaxMass)),
          lesson(number<C>(
              "k", "N/m", "floor spring constant per end", apply, [](C& c) -> double& { return c.params.k; },
              positive(kMaxStiffness))),
          number<C>(
              "floor_length", "m", "floor length from x = 0, 0 = unbounded", apply,
              [](C& c) -> double& { return c.params.floor_length; }, closed(0, kMaxSize)),
          number<C>(
              "floor_mu", "", "Coulomb friction of the floor at the rod's ends, 0 = frictionless", apply,
              [](C& c) -> double& { return c.params.floor_mu; }, closed(0, kMaxFriction)),
          lesson(number<C>(
              "x0", "m", "initial centre x", restart, [](C& c) -> double& { return c.initial.x; },
              closed(-kMaxSize, kMaxSize), "x")),
          // A centre under the floor is refused: a rod starts at or above it (it may lie on it, y0 = 0).
          lesson(number<C>(
              "y0", "m", "initial centre height", restart, [](C& c) -> double& { return c.initial.y; },
              closed(0, kMaxSize), "y")),
          lesson(number<C>(
              "vx0", "m/s", "initial velocity x", restart, [](C& c) -> double& { return c.initial.vx; },
              closed(-kMaxSpeed, kMaxSpeed), "vx")),
          lesson(number<C>(
              "vy0", "m/s", "initial velocity y", restart, [](C& c) -> double& { return c.initial.vy; },
              closed(-kMaxSpeed, kMaxSpeed), "vy")),
          lesson(number<C>(
              "theta0", "rad", "initial angle from +x", restart,
              [](C& c) -> double& { return c.initial.theta; }, closed(-kMaxAngle, kMaxAngle), "theta")),
          lesson(number<C>(
              "omega0", "rad/s", "initial angular velocity", restart,
              [](C& c) -> double& { return c.initial.omega; }, closed(-kMaxSpin, kMaxSpin), "omega")),
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

double theta0FromSeed(unsigned long long seed) {
  std::mt19937_64 generator(seed);
  const double unit = static_cast<double>(generator() >> 11) * 0x1.0p-53;
  return 2.0 * kPi * unit;
}

namespace {
void checkQuantities(const std::string& body, const RodConfig& config) {
  const Rod rod(config.params, config.initial);
  keys::checkDerived(body, "mass, length", "moment of inertia M L^2 / 12", rod.momentOfInertia(), true);
  keys::checkDerived(body, "k, mass", "omega_c = sqrt(4 k / mass)", rod.contactFrequency(), true);
  keys::checkDerived(body, "mass, length, k and the initial conditions", "energy at the start", rod.energy(),
                     false);
}
}  // namespace

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
  checkQuantities(body, config);
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

std::vector<std::string> RodType::extraFrames(const std::string& name) { return {groundFrameOf(name)}; }

bool RodType::touchesFloor(const Rod& rod) {
  if (inFlight(rod.params(), rod.state())) return false;
  // Rod::endHeightA / endHeightB's expressions, with one sine for both ends.
  const double y = rod.state().y;
  const double half = (0.5 * rod.params().length) * std::sin(rod.state().theta);
  return y + half < 0.0 || y - half < 0.0;
}

void RodType::checkState(const std::string& body, const Config& config, const RodMotion& state) {
  const double floor = config.params.floor_length;
  if (floor > 0.0 && !(state.x >= 0.0 && state.x <= floor)) {
    throw ConfigError(body, "x", formatNumber(state.x),
                      "a position on the floor, in [0, floor_length = " + formatNumber(floor) + "]");
  }
}

std::string slowRunWarning(const std::string& body, const RodConfig& config, double rate) {
  const int per_step = Rod(config.params, config.initial).substepsFor(1.0 / rate);
  const double per_second = per_step * rate;
  if (per_second <= kSlowSubstepsPerSecond) return "";
  return "body '" + body + "': k = " + formatNumber(config.params.k) +
         " with mass = " + formatNumber(config.params.mass) + " needs " + std::to_string(per_step) +
         " sub-steps per step at rate " + formatNumber(rate) + " (" + formatNumber(per_second) +
         " per simulated second): the run will be slow";
}

std::string autoSubstepNote(const std::string& body, const RodConfig& config, double rate) {
  if (config.params.substeps != kAutoSubsteps) return "";
  const Rod model(config.params, config.initial);
  const int n = model.autoSubstepsFor(1.0 / rate);
  if (n == 1) return "";
  return "body '" + body + "': substeps auto splits each step into " + std::to_string(n) +
         " sub-steps, as omega_c dt = " + formatNumber(model.contactFrequency() / rate) +
         " (omega_c = sqrt(4 k / mass) at k = " + formatNumber(config.params.k) +
         ", mass = " + formatNumber(config.params.mass) + ", rate = " + formatNumber(rate) + ") is above " +
         formatNumber(2.0 * Rod::kSubstepFraction) +
         "; substeps: N fixes the count instead (stable for N > omega_c dt / 2; 1 is the text's scheme)";
}

}  // namespace rigid_body_sim
