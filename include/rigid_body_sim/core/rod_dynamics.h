// The rod's forces and the single-step integrators, as free functions so that tests can drive them.
#pragma once

#include "rigid_body_sim/core/rod.h"

namespace rigid_body_sim {

// In flight: the centre at least L/2 up, so no end can be below the floor (|(L/2) sin theta| <= L/2 <= y)
// and neither spring acts. The force model, the energy and the bounce count skip their sines then.
inline bool inFlight(const RodParams& params, const RodMotion& state) {
  return state.y >= 0.5 * params.length;
}

// Linear and angular acceleration of the rod in a given state (the text's force model: the floor's springs
// and gravity; friction, which depends on the velocities and is not smooth, is applied by the steps).
struct RodAcceleration {
  double ax = 0.0;
  double ay = 0.0;
  double alpha = 0.0;
};
RodAcceleration rodAcceleration(const RodParams& params, const RodMotion& state);

// One step of each scheme, no sub-stepping. eulerCromerStep follows the text's program operation for
// operation (forces of end A, then end B, then gravity; v, then r; omega, then theta). With floor_mu > 0
// each also gives the floor's Coulomb friction as impulses on the velocities (physics.md, "Friction on the
// floor"): Euler-Cromer after its kick, Verlet after each half kick, RK4 half before and half after its
// stages. At floor_mu = 0 not one operation differs from the frictionless code.
RodMotion eulerCromerStep(const RodParams& params, const RodMotion& state, double dt);
RodMotion velocityVerletStep(const RodParams& params, const RodMotion& state, double dt);
RodMotion rk4Step(const RodParams& params, const RodMotion& state, double dt);
// `steps` steps of params.integrator, the same operations, in place: each result is stored field by field
// (a returned motion copied back waited on store forwarding, a fifth of a rod's step).
void advanceRod(const RodParams& params, RodMotion& state, double dt, int steps);

}  // namespace rigid_body_sim
