// What the bodies on an incline (the roller, the block) share: their common parameters, the events of a step
// and the instant a centre that moves at constant acceleration passes an end of its slope.
#pragma once

#include <optional>

#include "rigid_body_sim/core/constants.h"

namespace rigid_body_sim {

// The parameters every body on an incline has (core/types/key_builders.h, inclineKeys): the base of
// RollerParams and BlockParams.
struct InclineParams {
  double mass = 1.0;                 // kg
  double incline_angle = 0.349;      // rad, 0 <= phi < pi/2
  double incline_length = 5.0;       // m of slope; the centre runs over x in [0, incline_length]
  double mu_s = 0.3;                 // static friction coefficient
  double mu_d = 0.2;                 // kinetic friction coefficient, mu_d <= mu_s
  double gravity = kDefaultGravity;  // m/s^2
};

// What happened inside one step of a body on an incline, with the model's progress at each instant (from
// which the events' state fields are read: core/types/incline_events.h).
template <class Progress>
struct InclineStepEvents {
  std::optional<double> stuck_at;  // offset in [0, dt] at which it came to grip (rolls, or a block rests)
  bool started_slipping = false;   // a gripping body could not hold (only after setParams)
  std::optional<double> left_at;   // offset in (0, dt] at which the centre passed an end of the slope
  double arrival_speed = 0.0;      // its speed along the slope at left_at (m/s)
  bool restarted = false;          // the centre left the slope and the body restarted
  bool any() const { return started_slipping || stuck_at || left_at || restarted; }  // the common case: none
  // The model's progress at the step's start (when started_slipping), at stuck_at (gripping) and at left_at
  // (on the line, at its arrival speed): set with those, left uninitialised otherwise, so that a step
  // without an event does not clear them (zeroing them was half the cost of a roller's step).
  Progress at_start;
  Progress at_stuck;
  Progress at_left;
};

// The first s in (0, h] at which x + v s + a s^2 / 2 passes beyond [0, length] (above length, or below 0),
// given that the position after h is beyond it; the root is taken in its cancellation-free form.
double exitTime(double x, double v, double a, double h, double length);

// The first t in (0, duration] at which x + v t + a t^2 / 2 leaves [0, length], if any.
std::optional<double> firstExit(double x, double v, double a, double duration, double length);

}  // namespace rigid_body_sim
