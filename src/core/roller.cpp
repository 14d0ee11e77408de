// Round body on an incline: rolling / slipping with Coulomb friction, integrated in closed form.
#include "rigid_body_sim/core/roller.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rigid_body_sim {

double inertiaFactorOf(Shape shape) {
  switch (shape) {
    case Shape::Sphere: return 2.0 / 5.0;
    case Shape::Cylinder: return 1.0 / 2.0;
    case Shape::Ring: return 1.0;
    case Shape::SphericalShell: return 2.0 / 3.0;
    case Shape::Custom: break;
  }
  // A custom body carries its own c in RollerParams::inertia_factor.
  return std::numeric_limits<double>::quiet_NaN();
}

std::string toString(Shape shape) {
  switch (shape) {
    case Shape::Sphere: return "sphere";
    case Shape::Cylinder: return "cylinder";
    case Shape::Ring: return "ring";
    case Shape::SphericalShell: return "spherical_shell";
    case Shape::Custom: break;
  }
  return "custom";
}

const std::array<Shape, 4>& namedShapes() {
  static const std::array<Shape, 4> shapes = {Shape::Sphere, Shape::Cylinder, Shape::Ring,
                                              Shape::SphericalShell};
  return shapes;
}

std::optional<Shape> shapeFromString(const std::string& name) {
  // "custom" is deliberately not parsed: a custom body is described by its inertia factor instead.
  for (const Shape shape : namedShapes()) {
    if (toString(shape) == name) return shape;
  }
  return std::nullopt;
}

std::string toString(RollMode mode) {
  switch (mode) {
    case RollMode::Rolling: return "rolling";
    case RollMode::Slipping: return "slipping";
    case RollMode::Finished: break;
  }
  return "finished";
}

double criticalTangent(double mu_s, double inertia_factor) {
  return mu_s * (1.0 + inertia_factor) / inertia_factor;
}

double criticalAngle(double mu_s, double inertia_factor) {
  return std::atan(criticalTangent(mu_s, inertia_factor));
}

bool Roller::canRoll(const RollerParams& params) {
  return std::tan(params.incline_angle) <= criticalTangent(params.mu_s, params.inertia_factor);
}

Roller::Roller(const RollerParams& params, const RollerInitial& initial) : InclineBody(params, initial) {
  cacheAccelerations();
  reset();
}

void Roller::setParams(const RollerParams& params) {
  params_ = params;
  cacheAccelerations();
  // A slipping body keeps slipping until u reaches 0; only a rolling one can lose its grip here.
  if (mode_ == RollMode::Rolling && !canRoll(params_)) {
    mode_ = RollMode::Slipping;
    slip_sign_ = 1;  // gravity wins over static friction, so the contact point starts sliding downhill
    pending_started_slipping_ = true;
  }
}

void Roller::restore(const Progress& progress) {
  state_ = progress.state;
  mode_ = progress.mode;
  slip_sign_ = progress.slip_sign;
  laps_ = progress.laps;
  pending_started_slipping_ = progress.pending_started_slipping;
}

void Roller::enterModeFromState() {
  const double u = slipSpeed();
  if (u == 0.0) {
    // Exactly matched speeds: roll if static friction can hold, else gravity drags the contact downhill.
    mode_ = canRoll(params_) ? RollMode::Rolling : RollMode::Slipping;
    slip_sign_ = 1;
  } else {
    mode_ = RollMode::Slipping;
    slip_sign_ = u > 0.0 ? 1 : -1;
  }
}

int Roller::slipDirection() const { return slip_sign_; }

double Roller::slipSpeed() const { return state_.v + state_.omega * params_.radius; }

double Roller::normalForce() const { return params_.mass * params_.gravity * cos_angle_; }

double Roller::frictionForce() const {
  const double c = params_.inertia_factor;
  if (mode_ == RollMode::Finished) return 0.0;  // waiting at the line: nothing pushes it along the slope
  if (mode_ == RollMode::Rolling) {
    return -params_.mass * params_.gravity * sin_angle_ * c / (1.0 + c);
  }
  // Kinetic friction opposes the sliding of the contact point.
  return -slipDirection() * params_.mu_d * normalForce();
}

void Roller::cacheAccelerations() {
  sin_angle_ = std::sin(params_.incline_angle);
  cos_angle_ = std::cos(params_.incline_angle);
  const double c = params_.inertia_factor;
  const double r = params_.radius;
  const double g_along = params_.gravity * sin_angle_;
  const double rolling = g_along / (1.0 + c);
  accelerations_[0] = {rolling, -rolling / r};
  for (const int direction : {1, -1}) {
    // Kinetic friction opposes the sliding of the contact point (frictionForce() while slipping).
    const double friction = -direction * params_.mu_d * normalForce();
    // Torque about +z of friction f at the contact (0, -R): tau = R f, and I = c M R^2.
    accelerations_[direction > 0 ? 1 : 2] = {g_along + friction / params_.mass,
                                             friction / (c * params_.mass * r)};
  }
}

double Roller::acceleration() const { return current().a; }

double Roller::angularAcceleration() const { return current().alpha; }

double Roller::kineticEnergy() const {
  const double m = params_.mass;
  const double inertia = params_.inertia_factor * m * params_.radius * params_.radius;
  return 0.5 * m * state_.v * state_.v + 0.5 * inertia * state_.omega * state_.omega;
}

double Roller::energy() const {
  const double height_drop = state_.x * sin_angle_;
  return kineticEnergy() - params_.mass * params_.gravity * height_drop;
}

void Roller::advance(double h, double a, double alpha) {
  // Constant accelerations between events, so these updates are exact (up to rounding).
  state_.x += state_.v * h + 0.5 * a * h * h;
  state_.v += a * h;
  state_.theta += state_.omega * h + 0.5 * alpha * h * h;
  state_.omega += alpha * h;
}

namespace {
constexpr double kNever = std::numeric_limits<double>::infinity();
constexpr int kMaxPasses = 3;
}  // namespace

Roller::StepEvents Roller::step(double dt) {
  StepEvents events;
  beginStep(events);
  if (!(dt > 0.0) || finished()) return events;  // time only runs forward; a finished racer waits
  double elapsed = 0.0;
  // Each pass either ends the step or handles one u = 0 instant. After such an instant the body rolls
  // or slips forward with du/dt > 0 (see below), so two passes suffice; the bound only guards against
  // rounding making du/dt look negative right at the critical angle.
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    const double remaining = dt - elapsed;
    double to_zero = kNever;
    // Computed once a pass: the mode, and so the accelerations, change only after advance(to_zero).
    const double a = acceleration();
    const double alpha = angularAcceleration();
    if (mode_ == RollMode::Slipping && pass + 1 < kMaxPasses) {
      const double dudt = a + alpha * params_.radius;
      // u approaches 0 only when it changes against its own sign; clamp rounding-sized negative times.
      if (slipDirection() * dudt < 0.0) to_zero = std::max(0.0, -slipSpeed() / dudt);
    }
    const double h = to_zero <= remaining ? to_zero : remaining;
    if (holdsAtEnd(events, elapsed, h, a, alpha)) return events;
    if (!(to_zero <= remaining)) {
      advance(remaining, a, alpha);
      break;
    }
    advance(to_zero, a, alpha);
    elapsed += to_zero;
    state_.omega = -state_.v / params_.radius;  // land exactly on u = 0
    if (canRoll(params_)) {
      mode_ = RollMode::Rolling;
      events.stuck_at = elapsed;
      events.at_stuck = progress();
    } else {
      // Only a topspin body on a too-steep slope gets here; gravity then drags the contact downhill,
      // and du/dt > 0 because tan(phi) > mu_s (1+c)/c >= mu_d (1+c)/c.
      slip_sign_ = 1;
    }
  }
  endStep(events);
  return events;
}

}  // namespace rigid_body_sim

namespace rigid_body_sim {

// Section 16.3.2 in continuous time, phase by phase: slipping (sigma = sign of u = v + omega R) until u
// reaches 0, then rolling where static friction holds (else slipping forward); between the events every
// acceleration is constant.
RollerRun closedFormRun(const RollerParams& p, const RollerInitial& initial) {
  const double g = p.gravity;
  const double c = p.inertia_factor;
  const double sine = std::sin(p.incline_angle);
  const double cosine = std::cos(p.incline_angle);
  const bool can_roll = std::tan(p.incline_angle) <= criticalTangent(p.mu_s, c);
  const double rolling = g * sine / (1.0 + c);
  RollerRun run;
  double x = initial.x0;
  double v = initial.v0;
  double t = 0.0;
  const double u0 = initial.v0 + initial.omega0 * p.radius;
  if (u0 != 0.0 || !can_roll) {
    const double sigma = u0 < 0.0 ? -1.0 : 1.0;
    const double a = g * (sine - sigma * p.mu_d * cosine);
    const double dudt = g * sine - sigma * p.mu_d * g * cosine * (1.0 + c) / c;
    const double to_zero = sigma * dudt < 0.0 ? -u0 / dudt : kNever;
    if (const auto out = firstExit(x, v, a, to_zero, p.incline_length)) {
      run.finish = *out;
      return run;
    }
    if (to_zero == kNever) return run;
    x += v * to_zero + 0.5 * a * to_zero * to_zero;
    v += a * to_zero;
    t = to_zero;
    if (can_roll) run.slip_to_roll = t;
    const double after = can_roll ? rolling : g * (sine - p.mu_d * cosine);  // else slipping forward
    if (const auto out = firstExit(x, v, after, kNever, p.incline_length)) run.finish = t + *out;
    return run;
  }
  if (const auto out = firstExit(x, v, rolling, kNever, p.incline_length)) run.finish = *out;
  return run;
}

}  // namespace rigid_body_sim
