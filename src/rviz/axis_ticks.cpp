#include "rigid_body_sim/rviz/axis_ticks.h"

#include <algorithm>
#include <cmath>

#include "rigid_body_sim/core/parameters.h"

namespace rigid_body_sim {

AxisTicks niceTicks(double low, double high) {
  const double magnitude = std::max(std::abs(low), std::abs(high));
  const double least = std::max(0.2 * magnitude, 0.1);
  if (high - low < least) {
    const double middle = 0.5 * (low + high);
    low = middle - 0.5 * least;
    high = middle + 0.5 * least;
  }
  const double margin = 0.05 * (high - low);  // a line at the edge is drawn whole
  low -= margin;
  high += margin;
  const double raw = (high - low) / 5;
  int exponent = static_cast<int>(std::floor(std::log10(raw)));
  const double decade = std::pow(10.0, exponent);
  double mantissa = 1;
  if (raw > 5 * decade * (1 + 1e-9)) {
    ++exponent;  // 10 times the decade
  } else if (raw > 2 * decade * (1 + 1e-9)) {
    mantissa = 5;
  } else if (raw > decade * (1 + 1e-9)) {
    mantissa = 2;
  }
  const double step = mantissa * std::pow(10.0, exponent);
  const long first = static_cast<long>(std::floor(low / step));
  const long last = static_cast<long>(std::ceil(high / step));
  AxisTicks ticks{static_cast<double>(first) * step, static_cast<double>(last) * step, step, {}};
  for (long k = first; k <= last; ++k)
    ticks.labels.push_back(formatFixed(static_cast<double>(k) * step, std::max(0, -exponent)));
  return ticks;
}

}  // namespace rigid_body_sim
