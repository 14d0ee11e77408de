#include "rigid_body_sim/run/step_pacer.h"

#include <cmath>
#include <limits>

namespace rigid_body_sim {

StepPacer::StepPacer(double rate, double real_time_factor)
    : steps_per_wall_second_(rate * real_time_factor), real_time_factor_(real_time_factor) {}

void StepPacer::restart(double wall, std::int64_t steps) {
  anchor_wall_ = wall;
  anchor_steps_ = steps;
}

std::int64_t StepPacer::dueSteps(double wall) const {
  if (asFastAsPossible()) return std::numeric_limits<std::int64_t>::max();
  // The small allowance keeps a wake-up exactly at a step's due time from rounding just below it.
  const double elapsed_steps = (wall - anchor_wall_) * steps_per_wall_second_;
  return anchor_steps_ + static_cast<std::int64_t>(std::floor(elapsed_steps + 1e-6));
}

double StepPacer::wallTimeOf(std::int64_t steps) const {
  if (asFastAsPossible()) return anchor_wall_;
  return anchor_wall_ + static_cast<double>(steps - anchor_steps_) / steps_per_wall_second_;
}

}  // namespace rigid_body_sim
