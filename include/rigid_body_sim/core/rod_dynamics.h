// The rod's forces and the single-step integrators, as free functions so that tests can drive them.
#pragma once

#include "rigid_body_sim/core/rod.h"

namespace rigid_body_sim {

// In flight: the centre at least L/2 up, so no end can be below the floor (|(L/2) sin theta| <= L/2 <= y)
// and neither spring acts. The force model, the energy and the bounce count skip their sines then.
inline bool inFlight(const RodParams& params, const RodMotion& state) {
  return state.y >= 0.5 * params.length;
}

// Linear and angular acceleration of the rod in a given state (the text's force model).
struct RodAcceleration {
  double ax = 0.0;
  double ay = 0.0;
  double alpha = 0.0;
};
RodAcceleration rodAcceleration(const RodParams& params, const RodMotion& state);

// One step of each scheme, no sub-stepping. eulerCromerStep follows the text's program operation for
// operation (forces of end A, then end B, then gravity; v, then r; omega, then theta).
RodMotion eulerCromerStep(const RodParams& params, const RodMotion& state, double dt);
RodMotion velocityVerletStep(const RodParams& params, const RodMotion& state, double dt);
RodMotion rk4Step(const RodParams& params, const RodMotion& state, double dt);

}  // namespace rigid_body_sim
