// The rod as a stateful model: parameters, initial and current state, sub-stepped time stepping.
#include "rigid_body_sim/core/rod.h"

#include <cmath>
#include <limits>

#include "rigid_body_sim/core/rod_dynamics.h"

namespace rigid_body_sim {

std::string toString(Integrator integrator) {
  switch (integrator) {
    case Integrator::EulerCromer: return "euler_cromer";
    case Integrator::VelocityVerlet: return "velocity_verlet";
    case Integrator::Rk4: return "rk4";
  }
  return "unknown";  // unreachable for valid enumerators; keeps -Wreturn-type quiet
}

std::optional<Integrator> integratorFromString(const std::string& name) {
  for (Integrator i : {Integrator::EulerCromer, Integrator::VelocityVerlet, Integrator::Rk4}) {
    if (toString(i) == name) return i;
  }
  return std::nullopt;
}

std::string substepsToString(int substeps) {
  return substeps == kAutoSubsteps ? "auto" : std::to_string(substeps);
}

std::optional<int> substepsFromString(const std::string& text) {
  if (text == "auto") return kAutoSubsteps;
  if (text.empty() || text.size() > 10) return std::nullopt;
  long long value = 0;
  for (const char ch : text) {
    if (ch < '0' || ch > '9') return std::nullopt;
    value = value * 10 + (ch - '0');
  }
  if (value < 1 || value > kMaxSubsteps) return std::nullopt;
  return static_cast<int>(value);
}

Rod::Rod(const RodParams& params, const RodMotion& initial)
    : params_(params), initial_(initial), state_(initial) {}

RodStepEvents Rod::step(double dt) {
  // The last step's contacts, unless something moved the rod or changed its length since.
  const bool same = last_contacts_.length == params_.length && last_contacts_.y == state_.y &&
                    last_contacts_.theta == state_.theta;
  const unsigned before = same ? last_contacts_.ends : contacts();
  if (!(dt == substeps_.dt)) {
    const int n = substepsFor(dt);
    substeps_ = {dt, n, dt / n};  // n == 1 leaves dt bit-exact, so the text's run is unchanged
  }
  advanceRod(params_, state_, substeps_.h, substeps_.count);
  const bool restarted = !onFloor();
  if (restarted) state_ = initial_;  // off the end of a bounded floor: a new run from the initial conditions
  const unsigned after = contacts();
  last_contacts_ = {state_.y, state_.theta, params_.length, after};
  return RodStepEvents(before, after, restarted);
}

unsigned Rod::contacts() const {
  if (inFlight(params_, state_)) return 0;  // both ends above the floor, no sine needed
  // endHeightA and endHeightB's expressions, with one sine.
  const double half = (0.5 * params_.length) * std::sin(state_.theta);
  return (state_.y + half < 0.0 ? 1u : 0u) | (state_.y - half < 0.0 ? 2u : 0u);
}

bool Rod::onFloor() const {
  return params_.floor_length <= 0.0 || (state_.x >= 0.0 && state_.x <= params_.floor_length);
}

void Rod::setParams(const RodParams& params) {
  params_ = params;
  substeps_ = {};
}

void Rod::setInitial(const RodMotion& initial) {
  initial_ = initial;
  state_ = initial;
}

void Rod::reset() { state_ = initial_; }

void Rod::setState(const RodMotion& state) { state_ = state; }

double Rod::momentOfInertia() const {
  return (1.0 / 12.0) * params_.mass * (params_.length * params_.length);
}

double Rod::kineticEnergy() const {
  const RodMotion& s = state_;
  return 0.5 * params_.mass * (s.vx * s.vx + s.vy * s.vy) + 0.5 * momentOfInertia() * s.omega * s.omega;
}

double Rod::energy() const {
  const RodMotion& s = state_;
  const double kinetic = kineticEnergy();
  const double gravitational = params_.mass * params_.gravity * s.y;
  double elastic = 0.0;
  // In flight the elastic term is 0 without the sines: the same bits.
  if (!inFlight(params_, s)) {
    for (double y_end : {endHeightA(), endHeightB()}) {
      if (y_end < 0.0) elastic += 0.5 * params_.k * y_end * y_end;  // only a compressed spring stores energy
    }
  }
  return kinetic + gravitational + elastic;
}

// Same expressions as the force model, so that "below the floor" agrees with where a force acts.
double Rod::endHeightA() const { return state_.y + (0.5 * params_.length) * std::sin(state_.theta); }
double Rod::endHeightB() const { return state_.y - (0.5 * params_.length) * std::sin(state_.theta); }

double Rod::contactFrequency() const { return std::sqrt(4.0 * params_.k / params_.mass); }

int Rod::substepsFor(double dt) const {
  return params_.substeps == kAutoSubsteps ? autoSubstepsFor(dt) : params_.substeps;
}

// Euler-Cromer on a spring of angular frequency w is stable for w h < 2; one end of a flat rod (effective
// mass M/4) is the stiffest contact mode. Keep w h within kSubstepFraction of that bound.
int Rod::autoSubstepsFor(double dt) const {
  const double limit = 2.0 * kSubstepFraction;
  const double ratio = contactFrequency() * dt;
  if (!(ratio > limit)) return 1;  // also catches NaN
  const double n = std::ceil(ratio / limit);
  if (!(n < static_cast<double>(std::numeric_limits<int>::max()))) {
    return std::numeric_limits<int>::max();  // absurd stiffness: avoid an overflowing conversion
  }
  return static_cast<int>(n);
}

}  // namespace rigid_body_sim
