// The rod's force model and its integrators. Euler-Cromer reproduces the text's program bit for bit, so
// rodAcceleration keeps the text's order of operations (see test/rod_text_oracle.cpp for the original).
#include "rigid_body_sim/core/rod_dynamics.h"

#include <algorithm>
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

// Coulomb friction of the floor as impulses over a time h (physics.md, "Friction on the floor").
// ja, jb: the impulses along x at ends A and B, each within its bound ca, cb = mu N h. Of all those, the
// pair that leaves the least kinetic energy (maximal dissipation): it minimises
//   q(j) = 1/2 j^T W j + j^T v,  W = [[m + r, m - r], [m - r, m + r]],  m = 1/M, r = hy^2 / I,
// the kinetic energy the impulses add, where v = (va, vb) are the ends' slip velocities (x of V + w x r_end)
// and W maps impulses to slip changes (its diagonal is each end's 1/m_eff). j = 0 is allowed, so q <= 0:
// friction never adds kinetic energy. At the minimum an end below its bound has no slip left, and one at
// its bound slips against its impulse: static friction up to mu N, kinetic friction -mu N sign(slip).
struct EndImpulses {
  double a;
  double b;
};

double clampTo(double value, double bound) { return std::max(-bound, std::min(value, bound)); }

EndImpulses frictionImpulses(double m, double r, double vx, double va, double vb, double ca, double cb) {
  if (!(cb > 0.0)) return {clampTo(-va / (m + r), ca), 0.0};  // end A alone: 1 / m_eff = m + r
  if (!(ca > 0.0)) return {0.0, clampTo(-vb / (m + r), cb)};
  if (!(r > 0.0)) {
    // Flat (hy = 0): both ends slip at vx and only the sum of the impulses acts; shared as the loads are.
    const double sum = clampTo(-vx / m, ca + cb);
    const double a = sum * (ca / (ca + cb));
    return {a, sum - a};
  }
  // Unbounded minimum in sums and differences, q = m s^2 / 2 + s vx + r d^2 / 2 + d (va - vb) / 2: it stops
  // the translation (s = -M vx) and the spin (d). Taken when both impulses are within their bounds.
  const double s = -vx / m;
  const double d = (vb - va) / (2.0 * r);
  const EndImpulses free{0.5 * (s + d), 0.5 * (s - d)};
  if (std::fabs(free.a) <= ca && std::fabs(free.b) <= cb) return free;
  // Else the minimum is on the boundary of the box: the best of its four edges, each an exact minimum along
  // its edge. q is convex, so any minimiser gives the same velocities.
  const double diag = m + r, off = m - r;
  const auto q = [&](const EndImpulses& j) {
    return 0.5 * (diag * (j.a * j.a + j.b * j.b) + 2.0 * off * j.a * j.b) + j.a * va + j.b * vb;
  };
  const EndImpulses edges[] = {{ca, clampTo(-(vb + off * ca) / diag, cb)},
                               {-ca, clampTo(-(vb - off * ca) / diag, cb)},
                               {clampTo(-(va + off * cb) / diag, ca), cb},
                               {clampTo(-(va - off * cb) / diag, ca), -cb}};
  EndImpulses best = edges[0];
  double best_q = q(best);
  for (const EndImpulses& e : edges) {
    const double qe = q(e);
    if (qe < best_q) {
      best = e;
      best_q = qe;
    }
  }
  return best;
}

// The floor's friction over a time h on the velocities of `v` (vx and omega), with the normal forces
// N = -k y_end and lever arms of the positions of `at` (the same expressions as rodAcceleration, so that an
// end feels friction exactly where its spring pushes). The velocities of `at` are not read.
void floorFriction(const RodParams& p, const RodMotion& at, RodMotion& v, double h) {
  if (inFlight(p, at)) return;
  const double hy = (0.5 * p.length) * std::sin(at.theta);
  const double ya = at.y + hy;
  const double yb = at.y + (-hy);
  const double ca = ya < 0.0 ? p.floor_mu * (-p.k * ya) * h : 0.0;  // mu N h
  const double cb = yb < 0.0 ? p.floor_mu * (-p.k * yb) * h : 0.0;
  if (!(ca > 0.0) && !(cb > 0.0)) return;
  const double m = 1.0 / p.mass;
  const double inv_i = 1.0 / inertia(p);
  // End A at (hx, hy) from the centre slips at vx - omega hy, end B at (-hx, -hy) at vx + omega hy.
  const double va = v.vx - v.omega * hy;
  const double vb = v.vx + v.omega * hy;
  const EndImpulses j = frictionImpulses(m, hy * hy * inv_i, v.vx, va, vb, ca, cb);
  v.vx += (j.a + j.b) * m;
  v.omega += hy * (j.b - j.a) * inv_i;  // torque -r_y j: -hy ja at A, +hy jb at B
}

// Each step is compiled twice. Without friction, the text's floor (floor_mu = 0), it is the code it always
// was: the same operations on the state (so the same trajectory, bit for bit) and, but for the test of
// floor_mu, the same cost. With friction it is compiled apart and called out of line.
using StepFunction = RodMotion (*)(const RodParams&, const RodMotion&, double);
template <StepFunction kStep>
[[gnu::noinline]] RodMotion outOfLine(const RodParams& p, const RodMotion& s, double dt) {
  return kStep(p, s, dt);
}
template <StepFunction kFrictionless, StepFunction kWithFriction>
inline RodMotion stepOnFloor(const RodParams& p, const RodMotion& s, double dt) {
  if (__builtin_expect(p.floor_mu > 0.0, 0)) return outOfLine<kWithFriction>(p, s, dt);
  return kFrictionless(p, s, dt);
}

// Classic fourth-order Runge-Kutta on (x, y, theta, vx, vy, omega), without friction.
RodMotion rk4Conservative(const RodParams& p, const RodMotion& s, double dt) {
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

// Each scheme, with friction (kFriction) or without.
namespace {

// With friction: the springs and gravity kick the velocities, the friction impulse of dt (normal forces
// and lever arms still those of step i) acts on the kicked velocities, then the positions move with them.
template <bool kFriction>
RodMotion eulerCromer(const RodParams& p, const RodMotion& s, double dt) {
  const RodAcceleration a = rodAcceleration(p, s);
  RodMotion n;
  n.vx = s.vx + a.ax * dt;  // velocities first, then positions with the new velocities
  n.vy = s.vy + a.ay * dt;
  n.omega = s.omega + a.alpha * dt;
  if constexpr (kFriction) floorFriction(p, s, n, dt);  // at step i's positions
  n.x = s.x + n.vx * dt;
  n.y = s.y + n.vy * dt;
  n.theta = s.theta + n.omega * dt;
  return n;
}

// Kick-drift-kick: second order and symplectic; the force depends on positions only. Friction acts after
// each half kick, as an impulse of dt / 2 at that kick's positions.
template <bool kFriction>
RodMotion velocityVerlet(const RodParams& p, const RodMotion& s, double dt) {
  const double half = 0.5 * dt;
  const RodAcceleration a0 = rodAcceleration(p, s);
  RodMotion n = s;
  n.vx += half * a0.ax;
  n.vy += half * a0.ay;
  n.omega += half * a0.alpha;
  if constexpr (kFriction) floorFriction(p, n, n, half);
  n.x += dt * n.vx;
  n.y += dt * n.vy;
  n.theta += dt * n.omega;
  const RodAcceleration a1 = rodAcceleration(p, n);
  n.vx += half * a1.ax;
  n.vy += half * a1.ay;
  n.omega += half * a1.alpha;
  if constexpr (kFriction) floorFriction(p, n, n, half);
  return n;
}

// Friction, not smooth, stays out of the Runge-Kutta stages: half its impulse before them and half after
// (Strang splitting, first order in friction).
RodMotion rk4WithFriction(const RodParams& p, const RodMotion& s, double dt) {
  RodMotion start = s;
  floorFriction(p, s, start, 0.5 * dt);
  RodMotion n = rk4Conservative(p, start, dt);
  floorFriction(p, n, n, 0.5 * dt);
  return n;
}

}  // namespace

RodMotion eulerCromerStep(const RodParams& p, const RodMotion& s, double dt) {
  return stepOnFloor<eulerCromer<false>, eulerCromer<true>>(p, s, dt);
}

RodMotion velocityVerletStep(const RodParams& p, const RodMotion& s, double dt) {
  return stepOnFloor<velocityVerlet<false>, velocityVerlet<true>>(p, s, dt);
}

RodMotion rk4Step(const RodParams& p, const RodMotion& s, double dt) {
  return stepOnFloor<rk4Conservative, rk4WithFriction>(p, s, dt);
}

void advanceRod(const RodParams& p, RodMotion& s, double dt, int steps) {
  for (int i = 0; i < steps; ++i) {
    switch (p.integrator) {
      case Integrator::EulerCromer: s = stepOnFloor<eulerCromer<false>, eulerCromer<true>>(p, s, dt); break;
      case Integrator::VelocityVerlet:
        s = stepOnFloor<velocityVerlet<false>, velocityVerlet<true>>(p, s, dt);
        break;
      case Integrator::Rk4: s = stepOnFloor<rk4Conservative, rk4WithFriction>(p, s, dt); break;
    }
  }
}

}  // namespace rigid_body_sim
