// The lap and restart lifecycle of a body on an incline (the roller, the block), written once: its
// parameters, initial conditions, state, mode and laps, and what a step does at an end of the slope.
// Each body keeps its own physics (modes, accelerations, friction, energy) and its Progress.
#pragma once

#include <utility>

#include "rigid_body_sim/core/incline.h"

namespace rigid_body_sim {

// The base of Body (CRTP), which supplies, for this class (a friend) to call:
//   static Motion startingMotion(const Initial&);  the motion at the initial conditions
//   static void stop(Motion&);                     zeroes its velocities
//   void enterModeFromState();                     its mode as at a start, from the state and parameters
//   void advance(double h, double a, ...);         h seconds at constant accelerations
//   Progress progress() const;                     what a step changes
// Mode has an enumerator Finished: waiting at rest at the end of the slope.
template <class Body, class Params, class Initial, class Motion, class Mode>
class InclineBody {
 public:
  // Restarts from new initial conditions.
  void setInitial(const Initial& initial) {
    initial_ = initial;
    reset();
  }
  // Back to the initial conditions, lap 0.
  void reset() {
    state_ = Body::startingMotion(initial_);
    self().enterModeFromState();
    laps_ = 0;
    pending_started_slipping_ = false;
  }
  // A new lap from the initial conditions, as at the end of the slope.
  void restartLap() {
    state_ = Body::startingMotion(initial_);
    self().enterModeFromState();
    ++laps_;
  }
  // Moves it to `state` now, its mode following as at a start; the initial conditions and laps are kept.
  void setState(const Motion& state) {
    state_ = state;
    self().enterModeFromState();
    pending_started_slipping_ = false;
  }

  // In a race: a centre that passes an end of the slope stops there, at rest (mode Finished; the step's
  // events carry its arrival speed), instead of restarting, until restartLap().
  void setHoldAtEnd(bool hold) { hold_at_end_ = hold; }
  bool finished() const { return mode_ == Mode::Finished; }

  const Params& params() const { return params_; }
  const Initial& initial() const { return initial_; }
  const Motion& state() const { return state_; }
  Mode mode() const { return mode_; }
  int laps() const { return laps_; }

 protected:
  InclineBody(const Params& params, const Initial& initial) : params_(params), initial_(initial) {}

  // A step's first events: the grip that setParams lost since the last step.
  template <class Progress>
  void beginStep(InclineStepEvents<Progress>& events) {
    events.started_slipping = std::exchange(pending_started_slipping_, false);
    if (events.started_slipping) events.at_start = self().progress();
  }

  // For a stretch of h seconds from `elapsed` into the step at constant accelerations (a, rest...: as
  // Body::advance takes them): when the centre passes an end of the slope in it, records the instant and
  // the body on the line. True when it then holds there (a racer), which ends the step.
  template <class Progress, class... Rest>
  bool holdsAtEnd(InclineStepEvents<Progress>& events, double elapsed, double h, double a, Rest... rest) {
    const double x_after = state_.x + state_.v * h + 0.5 * a * h * h;  // as advance(h) computes it
    // Only the first crossing: past the end it is off its slope, restarting at the step's end.
    if (!events.left_at && (x_after > params_.incline_length || x_after < 0.0)) {
      const double s = exitTime(state_.x, state_.v, a, h, params_.incline_length);
      events.left_at = elapsed + s;
      // On the line, at the instant it passes it: a racer stops there and waits at rest.
      Body on_line = self();
      on_line.advance(s, a, rest...);
      on_line.state_.x = x_after > params_.incline_length ? params_.incline_length : 0.0;
      events.arrival_speed = on_line.state_.v;
      events.at_left = on_line.progress();
      if (hold_at_end_) {
        state_ = on_line.state_;
        Body::stop(state_);
        mode_ = Mode::Finished;
        return true;
      }
    }
    return false;
  }

  // The step's last event: off either end of the slope, a new lap from the initial conditions.
  template <class Progress>
  void endStep(InclineStepEvents<Progress>& events) {
    if (state_.x > params_.incline_length || state_.x < 0.0) {
      restartLap();
      events.restarted = true;
    }
  }

  Params params_;
  Initial initial_;
  Motion state_;
  Mode mode_{};  // the first mode until Body's constructor calls reset()
  int laps_ = 0;
  bool pending_started_slipping_ = false;  // set by setParams, reported by the next step
  bool hold_at_end_ = false;

 private:
  Body& self() { return static_cast<Body&>(*this); }
  const Body& self() const { return static_cast<const Body&>(*this); }
};

}  // namespace rigid_body_sim
