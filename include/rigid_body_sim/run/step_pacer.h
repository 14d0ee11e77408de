// Fixed-rate stepping against the wall clock: which step the simulation should have reached at a given
// wall time. Counting due steps from elapsed time (never from timer callbacks) means a late wake-up
// is caught up, and no step is ever lost or doubled.
#pragma once

#include <cstdint>

namespace rigid_body_sim {

class StepPacer {
 public:
  // real_time_factor: 1 = wall-clock pace, 2 = twice as fast, 0 = as fast as possible.
  StepPacer(double rate, double real_time_factor);

  // Anchors the pace: step `steps` is due at wall time `wall` (seconds). Call after a pause.
  void restart(double wall, std::int64_t steps);

  // The number of steps that should have been taken by wall time `wall` (unbounded when as fast as
  // possible).
  std::int64_t dueSteps(double wall) const;

  // The wall time at which step `steps` is due (the anchor's time when as fast as possible).
  double wallTimeOf(std::int64_t steps) const;

  bool asFastAsPossible() const { return real_time_factor_ <= 0.0; }

 private:
  double steps_per_wall_second_;
  double real_time_factor_;
  double anchor_wall_ = 0.0;
  std::int64_t anchor_steps_ = 0;
};

}  // namespace rigid_body_sim
