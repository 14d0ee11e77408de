// The roller's description (every key once) and its validation.
#include "rigid_body_sim/core/types/roller_type.h"

#include <cmath>

#include "key_builders.h"
#include "rigid_body_sim/core/parameters.h"

namespace rigid_body_sim {

using namespace keys;  // NOLINT: the builders of a description's rows

namespace {

std::vector<std::string> shapeNames() {
  std::vector<std::string> names;
  for (const Shape shape : namedShapes()) names.push_back(toString(shape));
  names.push_back(toString(Shape::Custom));
  return names;
}
void completeRoller(const std::string& body, const std::vector<std::string>& keys, RollerConfig& config) {
  const bool has_factor = given(keys, "inertia_factor");
  if (has_factor && !given(keys, "shape")) config.params.shape = Shape::Custom;
  if (config.params.shape == Shape::Custom && !has_factor) {
    throw ConfigError(body, "shape", "'custom'", "custom only with inertia_factor");
  }
}

void checkQuantities(const std::string& body, const RollerConfig& config) {
  const RollerParams& p = config.params;
  const double c_m_r = p.inertia_factor * p.mass * p.radius;  // friction / (c M R) is the spin's rate
  keys::checkDerived(body, "inertia_factor, mass, radius", "c M R", c_m_r, true);
  keys::checkDerived(body, "inertia_factor, mass, radius", "moment of inertia c M R^2", c_m_r * p.radius,
                     true);
  const Roller roller(p, config.initial);
  keys::checkDerived(body, "mass, radius and the initial conditions", "energy at the start", roller.energy(),
                     false);
}

// A named shape sets its c; custom keeps the c given (inertia_factor).
bool readShape(RollerConfig& config, const std::string& name) {
  if (name == toString(Shape::Custom)) {
    config.params.shape = Shape::Custom;
    return true;
  }
  const auto shape = shapeFromString(name);
  if (!shape) return false;
  config.params.shape = *shape;
  config.params.inertia_factor = inertiaFactorOf(*shape);
  return true;
}

}  // namespace

std::string modeText(const Roller& roller) { return toString(roller.mode()); }

const BodyType<RollerConfig>& RollerType::description() {
  using C = RollerConfig;
  constexpr auto apply = KeyChange::Apply;
  constexpr auto restart = KeyChange::Restart;
  static const BodyType<RollerConfig> type{
      RollerType::kName,
      concat<C>({
          {
              // Before inertia_factor: a named shape sets c, which a given inertia_factor then overrides
              // (and validation refuses unless it is the shape's).
              text<C>(
                  "shape", "shape (sets c unless custom)", apply,
                  [](const C& c) { return toString(c.params.shape); }, readShape, shapeNames),
              number<C>(
                  "inertia_factor", "", "c = I / (M R^2), used with shape custom", apply,
                  [](C& c) -> double& { return c.params.inertia_factor; }, positive(kMaxInertiaFactor)),
              number<C>(
                  "radius", "m", "radius", apply, [](C& c) -> double& { return c.params.radius; },
                  positive(kMaxSize)),
          },
          inclineKeys<C>(),  // mass, the slope and its friction, x0 and v0: as a block's
          {
              lesson(number<C>(
                  "theta0", "rad", "initial rotation", restart,
                  [](C& c) -> double& { return c.initial.theta0; }, closed(-kMaxAngle, kMaxAngle), "theta")),
              lesson(number<C>(
                  "omega0", "rad/s", "initial angular velocity", restart,
                  [](C& c) -> double& { return c.initial.omega0; }, closed(-kMaxSpin, kMaxSpin), "omega")),
          },
      }),
      completeRoller};
  return type;
}

void validate(const std::string& body, const RollerConfig& config) {
  checkRanges(body, config);
  const RollerParams& p = config.params;
  if (!gravityRange().contains(p.gravity)) {
    throw ConfigError(body, "gravity", formatNumber(p.gravity), gravityRange().describe());
  }
  checkFriction(body, p.mu_s, p.mu_d);
  checkOnSlope(body, "x0", config.initial.x0, p.incline_length);
  if (p.shape != Shape::Custom && p.inertia_factor != inertiaFactorOf(p.shape)) {
    throw ConfigError(body, "inertia_factor", formatNumber(p.inertia_factor),
                      "only with shape custom, or " + formatNumber(inertiaFactorOf(p.shape)) + " for shape " +
                          toString(p.shape));
  }
  checkQuantities(body, config);
}

void RollerType::checkState(const std::string& body, const Config& config, const RollerMotion& state) {
  checkOnSlope(body, "x", state.x, config.params.incline_length);
}

std::optional<double> RollerType::closedFormInstant(const Config& config, std::size_t kind) {
  if (kind != kGripped && kind != kFinished) return std::nullopt;
  const RollerRun run = closedFormRun(config.params, config.initial);
  return kind == kGripped ? run.slip_to_roll : run.finish;
}

}  // namespace rigid_body_sim
