// A block on an incline: sticking / sliding with Coulomb friction, integrated in closed form.
#include "rigid_body_sim/core/block.h"

#include <cmath>
#include <limits>

namespace rigid_body_sim {

namespace {
constexpr double kNever = std::numeric_limits<double>::infinity();
// Each pass ends the step or handles one stop; after a stop the block sticks or slides downhill for good
// (its speed then only grows), so two passes suffice.
constexpr int kMaxPasses = 2;

// The acceleration along the slope of a block moving with velocity sign `direction` (+1 downhill).
double slidingAcceleration(const BlockParams& p, double direction) {
  return p.gravity * (std::sin(p.incline_angle) - direction * p.mu_d * std::cos(p.incline_angle));
}
}  // namespace

std::string toString(BlockMode mode) {
  switch (mode) {
    case BlockMode::Sticking: return "sticking";
    case BlockMode::Sliding: return "sliding";
    case BlockMode::Finished: break;
  }
  return "finished";
}

bool Block::canStick(const BlockParams& params) { return std::tan(params.incline_angle) <= params.mu_s; }

Block::Block(const BlockParams& params, const BlockInitial& initial) : InclineBody(params, initial) {
  setParams(params);
  reset();
}

void Block::setParams(const BlockParams& params) {
  params_ = params;
  sin_angle_ = std::sin(params_.incline_angle);
  cos_angle_ = std::cos(params_.incline_angle);
  if (mode_ == BlockMode::Sticking && !canStick(params_)) {
    mode_ = BlockMode::Sliding;
    pending_started_slipping_ = true;
  }
}

void Block::restore(const Progress& progress) {
  state_ = progress.state;
  mode_ = progress.mode;
  laps_ = progress.laps;
  pending_started_slipping_ = progress.pending_started_slipping;
}

void Block::enterModeFromState() {
  mode_ = state_.v == 0.0 && canStick(params_) ? BlockMode::Sticking : BlockMode::Sliding;
}

double Block::normalForce() const { return params_.mass * params_.gravity * cos_angle_; }

double Block::frictionForce() const {
  switch (mode_) {
    case BlockMode::Sticking: return -params_.mass * params_.gravity * sin_angle_;  // holds it where it is
    case BlockMode::Sliding: {
      // Kinetic friction opposes the velocity; at rest on too steep a slope it is about to slide downhill.
      const double direction = state_.v < 0.0 ? -1.0 : 1.0;
      return -direction * params_.mu_d * normalForce();
    }
    case BlockMode::Finished: break;
  }
  return 0.0;  // waiting at the line: nothing pushes it along the slope
}

double Block::acceleration() const {
  if (mode_ != BlockMode::Sliding) return 0.0;
  return params_.gravity * sin_angle_ + frictionForce() / params_.mass;
}

double Block::kineticEnergy() const { return 0.5 * params_.mass * state_.v * state_.v; }

double Block::energy() const {
  return kineticEnergy() - params_.mass * params_.gravity * state_.x * sin_angle_;
}

void Block::advance(double h, double a) {
  state_.x += state_.v * h + 0.5 * a * h * h;  // exact at constant acceleration (up to rounding)
  state_.v += a * h;
}

Block::StepEvents Block::step(double dt) {
  StepEvents events;
  beginStep(events);
  if (!(dt > 0.0) || mode_ != BlockMode::Sliding) return events;  // a sticking or finished block stays
  double elapsed = 0.0;
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    const double remaining = dt - elapsed;
    const double a = acceleration();
    // Friction decelerates it when a opposes v: it stops at -v / a, unless the slope's end comes first.
    const double to_stop = state_.v * a < 0.0 ? -state_.v / a : kNever;
    const double h = to_stop <= remaining ? to_stop : remaining;
    if (holdsAtEnd(events, elapsed, h, a)) return events;
    if (!(to_stop <= remaining)) {
      advance(remaining, a);
      break;
    }
    advance(to_stop, a);
    elapsed += to_stop;
    state_.v = 0.0;  // land exactly at rest
    if (canStick(params_)) {
      mode_ = BlockMode::Sticking;
      events.stuck_at = elapsed;
      events.at_stuck = progress();
      break;
    }
    // Stopped on its way uphill on a slope too steep to hold it: it slides back down.
  }
  endStep(events);
  return events;
}

// In continuous time, phase by phase: a moving block decelerates or speeds up at constant acceleration
// until it stops or leaves the slope; at rest it sticks, or slides downhill.
BlockRun closedFormRun(const BlockParams& p, const BlockInitial& initial) {
  BlockRun run;
  double x = initial.x0;
  double v = initial.v0;
  double t = 0.0;
  const bool sticks = std::tan(p.incline_angle) <= p.mu_s;
  if (v != 0.0) {
    const double a = slidingAcceleration(p, v < 0.0 ? -1.0 : 1.0);
    const double to_stop = v * a < 0.0 ? -v / a : kNever;
    if (const auto out = firstExit(x, v, a, to_stop, p.incline_length)) {
      run.finish = *out;
      return run;
    }
    if (to_stop == kNever) return run;
    x += v * to_stop + 0.5 * a * to_stop * to_stop;
    t = to_stop;
    run.stops = t;
  }
  if (sticks) return run;
  if (const auto out = firstExit(x, 0.0, slidingAcceleration(p, 1.0), kNever, p.incline_length)) {
    run.finish = t + *out;
  }
  return run;
}

}  // namespace rigid_body_sim
