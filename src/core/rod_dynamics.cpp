// The rod's force model and its integrators. Euler-Cromer reproduces the text's program bit for bit, so
// rodAcceleration keeps the text's order of operations (see test/rod_text_oracle.cpp for the original).
#include "rigid_body_sim/core/rod_dynamics.h"

#include <cmath>

namespace rigid_body_sim {
namespace {

// Force and torque of one end's floor spring. (hx, hy) is the end's offset from the centre; the lever
// arm is recomputed as end - centre, as the text does, not taken as (hx, hy), to round the same way.
struct EndLoad {
  double fx;
  double fy;
  double torque;
};
EndLoad endLoad(double x, double y, double hx, double hy, double k) {
  const double ex = x + hx;
  const double ey = y + hy;
  // The text multiplies by the boolean (dr < 0) and then by the vector (0, 1, 0): keep both products,
  // so that even the signed zeros match.
  const double push = (-k * ey) * (ey < 0.0 ? 1.0 : 0.0);
  const double fx = push * 0.0;
  const double fy = push * 1.0;
  const double lx = ex - x;
  const double ly = ey - y;
  return {fx, fy, lx * fy - ly * fx};  // z of cross(lever, f), numpy's order
}

double inertia(const RodParams& p) { return (1.0 / 12.0) * p.mass * (p.length * p.length); }

// State derivative for RK4: (x, y, theta, vx, vy, omega)' = (vx, vy, omega, ax, ay, alpha).
RodMotion derivative(const RodParams& p, const RodMotion& s) {
  const RodAcceleration a = rodAcceleration(p, s);
  return {s.vx, s.vy, s.omega, a.ax, a.ay, a.alpha};
}

// s + h * d, component by component.
RodMotion advance(const RodMotion& s, const RodMotion& d, double h) {
  return {s.x + h * d.x,   s.y + h * d.y,   s.theta + h * d.theta,
          s.vx + h * d.vx, s.vy + h * d.vy, s.omega + h * d.omega};
}

}  // namespace

RodAcceleration rodAcceleration(const RodParams& p, const RodMotion& s) {
  const double half = 0.5 * p.length;
  const double weight = p.mass * p.gravity;
  if (inFlight(p, s)) {
    // Both springs give signed zeros, and the sums below come to exactly these values: the same bits
    // without cos and sin, which are most of a step's cost.
    return {0.0 / p.mass, (0.0 - weight * 1.0) / p.mass, 0.0 / inertia(p)};
  }
  const double hx = half * std::cos(s.theta);
  const double hy = half * std::sin(s.theta);
  const EndLoad a = endLoad(s.x, s.y, hx, hy, p.k);    // end A = R + (L/2) u
  const EndLoad b = endLoad(s.x, s.y, -hx, -hy, p.k);  // end B = R - (L/2) u (x + (-h) == x - h)
  const double fx = ((0.0 + a.fx) + b.fx) - weight * 0.0;
  const double fy = ((0.0 + a.fy) + b.fy) - weight * 1.0;
  const double tz = (0.0 + a.torque) + b.torque;
  return {fx / p.mass, fy / p.mass, tz / inertia(p)};
}

RodMotion eulerCromerStep(const RodParams& p, const RodMotion& s, double dt) {
  const RodAcceleration a = rodAcceleration(p, s);
  RodMotion n;
  n.vx = s.vx + a.ax * dt;  // velocities first, then positions with the new velocities
  n.vy = s.vy + a.ay * dt;
  n.x = s.x + n.vx * dt;
  n.y = s.y + n.vy * dt;
  n.omega = s.omega + a.alpha * dt;
  n.theta = s.theta + n.omega * dt;
  return n;
}

// Kick-drift-kick: second order and symplectic; the force depends on positions only.
RodMotion velocityVerletStep(const RodParams& p, const RodMotion& s, double dt) {
  const double half = 0.5 * dt;
  const RodAcceleration a0 = rodAcceleration(p, s);
  RodMotion n = s;
  n.vx += half * a0.ax;
  n.vy += half * a0.ay;
  n.omega += half * a0.alpha;
  n.x += dt * n.vx;
  n.y += dt * n.vy;
  n.theta += dt * n.omega;
  const RodAcceleration a1 = rodAcceleration(p, n);
  n.vx += half * a1.ax;
  n.vy += half * a1.ay;
  n.omega += half * a1.alpha;
  return n;
}

// Classic fourth-order Runge-Kutta on (x, y, theta, vx, vy, omega).
RodMotion rk4Step(const RodParams& p, const RodMotion& s, double dt) {
  const RodMotion k1 = derivative(p, s);
  const RodMotion k2 = derivative(p, advance(s, k1, 0.5 * dt));
  const RodMotion k3 = derivative(p, advance(s, k2, 0.5 * dt));
  const RodMotion k4 = derivative(p, advance(s, k3, dt));
  const auto mix = [](double d1, double d2, double d3, double d4) {
    return (d1 + 2.0 * d2 + 2.0 * d3 + d4) / 6.0;
  };
  const RodMotion slope{mix(k1.x, k2.x, k3.x, k4.x),
                        mix(k1.y, k2.y, k3.y, k4.y),
                        mix(k1.theta, k2.theta, k3.theta, k4.theta),
                        mix(k1.vx, k2.vx, k3.vx, k4.vx),
                        mix(k1.vy, k2.vy, k3.vy, k4.vy),
                        mix(k1.omega, k2.omega, k3.omega, k4.omega)};
  return advance(s, slope, dt);
}

}  // namespace rigid_body_sim
