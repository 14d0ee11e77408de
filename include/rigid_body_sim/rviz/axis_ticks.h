// A chart axis's ticks as people read them (the panel's charts): round steps, distinct labels, no "-0".
#pragma once

#include <string>
#include <vector>

namespace rigid_body_sim {

struct AxisTicks {
  double low;  // the axis's range: the first and last tick
  double high;
  double step;
  std::vector<std::string> labels;  // from low to high, one per step
};

// For values in [low, high]: about five steps of 1, 2 or 5 times a power of ten, a margin of 5 % inside the
// range, each label written with the decimals the step needs (so they are distinct numbers) and never "-0".
// A flat range (a constant force) is first widened to a fifth of its size around it (0.1 at least): a
// readable span, not the noise of its last digits.
AxisTicks niceTicks(double low, double high);

}  // namespace rigid_body_sim
