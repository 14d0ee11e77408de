// What the bodies on an incline (the roller, the block) share: the events of a step and the instant a
// centre that moves at constant acceleration passes an end of its slope.
#pragma once

#include <optional>

namespace rigid_body_sim {

// What happened inside one step of a body on an incline, with the model's progress at each instant (from
// which the events' state fields are read: core/types/incline_events.h).
template <class Progress>
struct InclineStepEvents {
  std::optional<double> stuck_at;    // offset in [0, dt] at which it came to grip (rolls, or a block rests)
  bool started_slipping = false;     // a gripping body could not hold (only after setParams)
  std::optional<double> left_at;     // offset in (0, dt] at which the centre passed an end of the slope
  double arrival_speed = 0.0;        // its speed along the slope at left_at (m/s)
  bool restarted = false;            // the centre left the slope and the body restarted
  std::optional<Progress> at_start;  // at the step's start, when started_slipping
  std::optional<Progress> at_stuck;  // at stuck_at, gripping
  std::optional<Progress> at_left;   // at left_at: on the line, at its arrival speed
};

// The first s in (0, h] at which x + v s + a s^2 / 2 passes beyond [0, length] (above length, or below 0),
// given that the position after h is beyond it; the root is taken in its cancellation-free form.
double exitTime(double x, double v, double a, double h, double length);

// The first t in (0, duration] at which x + v t + a t^2 / 2 leaves [0, length], if any.
std::optional<double> firstExit(double x, double v, double a, double duration, double length);

}  // namespace rigid_body_sim
