// The events and the slope's ends shared by the bodies on an incline.
#include "rigid_body_sim/core/incline.h"

#include <algorithm>
#include <cmath>

namespace rigid_body_sim {

double exitTime(double x, double v, double a, double h, double length) {
  const double end = x + v * h + 0.5 * a * h * h > length ? length : 0.0;
  // a s^2 / 2 + v s - (end - x) = 0: s = 2 d / (v + sign(v) sqrt(v^2 + 2 a d)) avoids the cancellation of
  // -v + sqrt(...) when a s is small beside v; with v = 0 the root is sqrt(2 d / a).
  const double d = end - x;
  const double root = std::sqrt(std::max(0.0, v * v + 2.0 * a * d));
  const double s = v == 0.0 ? std::sqrt(std::max(0.0, 2.0 * d / a)) : 2.0 * d / (v + std::copysign(root, v));
  return std::clamp(s, 0.0, h);
}

// The smallest root in (0, duration] of reaching either end, each end's roots in their cancellation-free
// form.
std::optional<double> firstExit(double x, double v, double a, double duration, double length) {
  std::optional<double> first;
  for (const double end : {length, 0.0}) {
    const double d = end - x;  // a t^2 / 2 + v t - d = 0
    const double discriminant = v * v + 2.0 * a * d;
    if (discriminant < 0.0) continue;
    const double q = -0.5 * (v + std::copysign(std::sqrt(discriminant), v == 0.0 ? 1.0 : v));
    // Roots: q / (a / 2) and -d / q (Numerical Recipes' form of the quadratic formula).
    for (const double t : {a != 0.0 ? q / (0.5 * a) : -1.0, q != 0.0 ? -d / q : -1.0}) {
      if (t > 0.0 && t <= duration && (!first || t < *first)) first = t;
    }
  }
  return first;
}

}  // namespace rigid_body_sim
