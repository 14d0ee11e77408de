// Coulomb friction on the rod's floor (floor_mu, physics.md "Friction on the floor"): a rod sliding flat
// stops where mu g says and stays stopped, friction never adds energy, pushes each end against its slip
// and never reverses it within a step. At floor_mu = 0 the text's program is reproduced bit for bit by
// test_rod's oracle tests, which run with the default floor_mu = 0.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "rigid_body_sim/core/rod.h"
#include "rigid_body_sim/core/rod_dynamics.h"
#include "rigid_body_sim/core/world.h"
#include "rigid_body_sim/io/config_loader.h"
#include "test_util.h"

namespace rigid_body_sim {
namespace {

constexpr double kG = 9.8;
constexpr double kTextDt = 0.001;
const std::vector<Integrator> kIntegrators = {Integrator::EulerCromer, Integrator::VelocityVerlet,
                                              Integrator::Rk4};

RodParams frictionParams(Integrator integrator, double mu) {
  RodParams p;  // the text's rod: L = 1 m, M = 0.5 kg, k = 1000 N/m, g = 9.8 m/s^2
  p.integrator = integrator;
  p.floor_mu = mu;
  return p;
}

RodMotion stepOf(const RodParams& p, const RodMotion& s, double dt) {
  switch (p.integrator) {
    case Integrator::EulerCromer: return eulerCromerStep(p, s, dt);
    case Integrator::VelocityVerlet: return velocityVerletStep(p, s, dt);
    case Integrator::Rk4: return rk4Step(p, s, dt);
  }
  return s;
}

double energyOf(const RodParams& p, const RodMotion& s) { return Rod(p, s).energy(); }
double kineticOf(const RodParams& p, const RodMotion& s) { return Rod(p, s).kineticEnergy(); }

// Height of an end (sign +1: A, -1: B) and its slip: x of V + omega x r_end, r_end = +-(L/2)(cos, sin).
double endHeight(const RodParams& p, const RodMotion& s, int sign) {
  return s.y + sign * (0.5 * p.length) * std::sin(s.theta);
}
double endSlip(const RodParams& p, const RodMotion& s, int sign) {
  return s.vx - s.omega * sign * (0.5 * p.length) * std::sin(s.theta);
}

// ------------------------------------------------------------------------------------------------
// 1. A rod lying flat at its spring equilibrium, sliding at v0: it stops after v0 / (mu g), having gone
// v0^2 / (2 mu g), and stays where it stopped.

TEST(RodFriction, FlatRodSlidingStopsAsMuGSays) {
  const double dt = 1e-4, v0 = 2.0;
  for (Integrator integrator : kIntegrators) {
    for (double mu : {0.2, 0.5, 1.0}) {
      const RodParams p = frictionParams(integrator, mu);
      // Each end compressed by M g / (2 k): the springs carry the weight, so N_A + N_B = M g.
      const RodMotion start{0.0, -p.mass * p.gravity / (2.0 * p.k), 0.0, v0, 0.0, 0.0};
      ASSERT_LT(endHeight(p, start, 1), 0.0);
      ASSERT_LT(endHeight(p, start, -1), 0.0);
      const double t_exact = v0 / (mu * kG), d_exact = v0 * v0 / (2.0 * mu * kG);
      RodMotion s = start;
      int n = 0;
      double lowest_vx = v0;
      while (s.vx > 1e-12 && n < 10 * static_cast<int>(t_exact / dt)) {
        const double before = s.vx;
        s = stepOf(p, s, dt);
        ++n;
        ASSERT_LE(s.vx, before) << "friction pushed a sliding rod forward";
        lowest_vx = std::min(lowest_vx, s.vx);
      }
      const double t_stop = n * dt, d_stop = s.x - start.x;
      // Each step takes mu g dt off vx (mu (N_A + N_B) dt / M), the last one only what is left: vx reaches
      // 0 within one step after t_exact, and never goes below. x adds up vx dt, a Riemann sum of the
      // decreasing v0 - mu g t: within (v0 + mu g dt) dt of its integral (2e-4 m of 0.41 m at mu = 0.5,
      // 5e-4 relative). Measured: v0 dt / 2 for Euler-Cromer; ~1e-8 relative for Verlet and RK4, whose
      // half impulses make it a trapezoid sum.
      std::printf(
          "[ slide  ] %-15s mu %.1f: stops at %.4f s (v0/(mu g) %.6f), after %.6f m (%.6f), rel. "
          "%.1e / %.1e\n",
          toString(integrator).c_str(), mu, t_stop, t_exact, d_stop, d_exact, (t_stop - t_exact) / t_exact,
          (d_stop - d_exact) / d_exact);
      EXPECT_GE(t_stop, t_exact - 1e-9) << toString(integrator) << " mu " << mu;
      EXPECT_LE(t_stop, t_exact + dt + 1e-9) << toString(integrator) << " mu " << mu;
      EXPECT_NEAR(d_stop, d_exact, mu * kG * dt * (t_exact + dt)) << toString(integrator) << " mu " << mu;
      EXPECT_GT(lowest_vx, -1e-12) << "overshot past zero";
      // Stuck for the next 10 s: no creep, no chatter. A chattering end would swing vx by mu g dt (1e-3 m/s
      // at mu = 1) each step; what is left is the rounding of mu N dt impulses (~1e-20 m/s).
      const RodMotion stopped = s;
      double max_vx = 0.0, max_dx = 0.0;
      for (int i = 0; i < static_cast<int>(10.0 / dt); ++i) {
        s = stepOf(p, s, dt);
        max_vx = std::max(max_vx, std::fabs(s.vx));
        max_dx = std::max(max_dx, std::fabs(s.x - stopped.x));
      }
      std::printf("[ stuck  ] %-15s mu %.1f: over 10 s max |vx| %.2e m/s, max |x - x_stop| %.2e m\n",
                  toString(integrator).c_str(), mu, max_vx, max_dx);
      EXPECT_LE(max_vx, 1e-12) << toString(integrator) << " mu " << mu;
      EXPECT_LE(max_dx, 1e-12) << toString(integrator) << " mu " << mu;
    }
  }
}

// On a stiff floor (k = 1e6 N/m, omega_c dt = 2.8) each step of dt = 1 ms is split into 29 sub-steps
// (substeps: auto), each with its own impulse: the rod still stops within one step after v0 / (mu g).
TEST(RodFriction, SubStepsOfAStiffFloorStopItAsMuGSays) {
  const double v0 = 2.0, mu = 0.5;
  for (Integrator integrator : kIntegrators) {
    RodParams p = frictionParams(integrator, mu);
    p.k = 1e6;
    const RodMotion start{0.0, -p.mass * p.gravity / (2.0 * p.k), 0.0, v0, 0.0, 0.0};
    Rod rod(p, start);
    ASSERT_EQ(rod.substepsFor(kTextDt), 29);
    int n = 0;
    while (rod.state().vx > 1e-12 && n < 10000) rod.step(kTextDt), ++n;
    const double t_exact = v0 / (mu * kG), d_exact = v0 * v0 / (2.0 * mu * kG);
    std::printf("[ stiff  ] %-15s stops at %.3f s (v0/(mu g) %.6f), after %.6f m (%.6f)\n",
                toString(integrator).c_str(), n * kTextDt, t_exact, rod.state().x, d_exact);
    EXPECT_GE(n * kTextDt, t_exact - 1e-9) << toString(integrator);
    EXPECT_LE(n * kTextDt, t_exact + kTextDt + 1e-9) << toString(integrator);
    EXPECT_NEAR(rod.state().x, d_exact, mu * kG * kTextDt * (t_exact + kTextDt)) << toString(integrator);
  }
}

// ------------------------------------------------------------------------------------------------
// 2. The law, step by step. An Euler-Cromer step with friction and the frictionless step from the same
// state have the same kick and differ only by the friction impulses, applied before the positions move:
// so from the two, each end's impulse and its slip before and after friction are known exactly.

struct FrictionCheck {
  int contacts = 0, two_ends = 0, stuck = 0;  // steps seen with one end / two ends in contact, stuck ends
  double worst_ke_gain = 0.0;                 // the largest kinetic energy friction added (J)
};

// Checks one Euler-Cromer step from s against Coulomb's law; accumulates into `c`.
void checkCoulombStep(const RodParams& p, const RodMotion& s, double dt, FrictionCheck& c) {
  RodParams p0 = p;
  p0.floor_mu = 0.0;
  const RodMotion pre = eulerCromerStep(p0, s, dt);  // the kicked velocities, before friction
  const RodMotion post = eulerCromerStep(p, s, dt);
  ASSERT_EQ(post.vy, pre.vy);  // friction is along x only
  // Kinetic energy of the velocities alone (the positions do not enter it).
  const double ke_pre = kineticOf(p, pre), ke_post = kineticOf(p, post);
  c.worst_ke_gain = std::max(c.worst_ke_gain, ke_post - ke_pre);
  EXPECT_LE(ke_post, ke_pre * (1.0 + 1e-15)) << "friction added kinetic energy";
  const double inertia = Rod(p, s).momentOfInertia();
  const double hy = (0.5 * p.length) * std::sin(s.theta);
  const double momentum = p.mass * (post.vx - pre.vx);        // j_A + j_B
  const double angular = inertia * (post.omega - pre.omega);  // -hy j_A + hy j_B
  const bool in_a = endHeight(p, s, 1) < 0.0, in_b = endHeight(p, s, -1) < 0.0;
  if (!in_a && !in_b) {
    EXPECT_EQ(post.vx, pre.vx);
    EXPECT_EQ(post.omega, pre.omega);
    return;
  }
  double j[2];
  if (in_a && in_b) {
    if (std::fabs(hy) < 1e-3) return;  // the split of the two impulses is ill-conditioned: not checked
    ++c.two_ends;
    j[0] = 0.5 * (momentum - angular / hy);
    j[1] = 0.5 * (momentum + angular / hy);
  } else {
    ++c.contacts;
    j[0] = in_a ? momentum : 0.0;
    j[1] = in_a ? 0.0 : momentum;
    EXPECT_NEAR(angular, (in_a ? -hy : hy) * momentum, 1e-12 * (1.0 + std::fabs(momentum)));
  }
  for (int end = 0; end < 2; ++end) {
    const int sign = end == 0 ? 1 : -1;
    const double y_end = endHeight(p, s, sign);
    if (!(y_end < 0.0)) continue;
    const double bound = p.floor_mu * (-p.k * y_end) * dt;  // mu N dt
    const double before = endSlip(p, RodMotion{s.x, s.y, s.theta, pre.vx, pre.vy, pre.omega}, sign);
    const double after = endSlip(p, RodMotion{s.x, s.y, s.theta, post.vx, post.vy, post.omega}, sign);
    const double tol = 1e-9 * (bound + std::fabs(before) * p.mass);  // rounding of the recovered impulses
    EXPECT_LE(std::fabs(j[end]), bound + tol) << "static friction beyond mu N";
    EXPECT_LE(j[end] * after, tol) << "friction along the slip it leaves";
    if (std::fabs(j[end]) < bound - tol) {  // below mu N: the end sticks
      ++c.stuck;
      EXPECT_LE(std::fabs(after), 1e-9) << "an end below mu N still slips";
    }
    if (in_a != in_b) {  // one end: it is pushed against its slip, and never beyond zero slip
      EXPECT_LE(j[end] * before, 0.0) << "an end sliding +x must be pushed -x";
      // A stuck end is left with the rounding of vx - omega hy (~1e-16 m/s), of either sign; a reversal by
      // friction would be of order mu g dt (1e-3 m/s).
      EXPECT_TRUE(after * before >= 0.0 || std::fabs(after) <= 1e-12)
          << "slip reversed within a step: " << before << " -> " << after;
    }
  }
}

// States along bouncing runs with spin (with friction), and states drawn near the floor.
TEST(RodFriction, EachStepIsCoulombsLaw) {
  for (double mu : {0.1, 0.5, 2.0}) {
    const RodParams p = frictionParams(Integrator::EulerCromer, mu);
    FrictionCheck c;
    for (double theta0 : {0.3, 1.0, 2.5, 4.0}) {
      for (double omega0 : {-8.0, 0.0, 8.0}) {
        RodMotion s{0.0, 4.0, theta0, 2.0, 0.0, omega0};
        for (int n = 0; n < 10000; ++n) {
          checkCoulombStep(p, s, kTextDt, c);
          s = eulerCromerStep(p, s, kTextDt);
        }
      }
    }
    // A flat or nearly flat rod pressed into the floor (both ends in contact), sliding and spinning.
    for (int i = 0; i < 2000; ++i) {
      const double u = (i % 97) / 96.0, w = (i % 89) / 88.0, z = (i % 83) / 82.0;
      const RodMotion s{
          0.0, -0.02 * u, 0.06 * (w - 0.5), 2.0 * (z - 0.5), -0.5, 20.0 * (u - 0.5) * (w - 0.3)};
      checkCoulombStep(p, s, kTextDt, c);
    }
    std::printf(
        "[ coulomb] mu %.1f: %d one-end and %d two-end steps checked, %d stuck ends, largest kinetic "
        "energy gain %.2e J\n",
        mu, c.contacts, c.two_ends, c.stuck, c.worst_ke_gain);
    EXPECT_GT(c.contacts, 100);
    EXPECT_GT(c.two_ends, 100);
    EXPECT_GT(c.stuck, 10);
  }
}

// ------------------------------------------------------------------------------------------------
// 3. Energy over whole bouncing runs (the text's values, 10 s): friction only takes energy away.

const std::vector<double> kTheta0s = {0.0, 0.3, 1.0, 1.5707963267948966, 2.5, 4.0, 5.5};

// The largest rise of the energy over one step, over `steps` steps from `start`; the energy at the end.
struct EnergyRun {
  double largest_rise = 0.0;
  double end = 0.0;
};
EnergyRun energyRun(const RodParams& p, const RodMotion& start, int steps) {
  Rod rod(p, start);
  EnergyRun r;
  for (int n = 0; n < steps; ++n) {
    const double before = rod.energy();
    rod.step(kTextDt);
    r.largest_rise = std::max(r.largest_rise, rod.energy() - before);
  }
  r.end = rod.energy();
  return r;
}

TEST(RodFriction, TakesEnergyAwayOverBouncingRuns) {
  for (Integrator integrator : kIntegrators) {
    // The integrator's own fluctuation: the largest one-step rise of the frictionless runs.
    double frictionless_rise = 0.0;
    std::vector<double> frictionless_end;
    for (double theta0 : kTheta0s) {
      const EnergyRun r =
          energyRun(frictionParams(integrator, 0.0), {0.0, 4.0, theta0, 2.0, 0.0, 0.0}, 10000);
      frictionless_rise = std::max(frictionless_rise, r.largest_rise);
      frictionless_end.push_back(r.end);
    }
    for (double mu : {0.1, 0.5, 2.0}) {
      double rise = 0.0, lowest_ratio = 1.0, worst_ratio = 0.0;
      for (std::size_t i = 0; i < kTheta0s.size(); ++i) {
        const EnergyRun r =
            energyRun(frictionParams(integrator, mu), {0.0, 4.0, kTheta0s[i], 2.0, 0.0, 0.0}, 10000);
        rise = std::max(rise, r.largest_rise);
        lowest_ratio = std::min(lowest_ratio, r.end / frictionless_end[i]);
        worst_ratio = std::max(worst_ratio, r.end / frictionless_end[i]);
        EXPECT_LT(r.end, frictionless_end[i])
            << toString(integrator) << " mu " << mu << " theta0 " << kTheta0s[i];
      }
      std::printf(
          "[ energy ] %-15s mu %.1f: largest one-step rise %.4f J (frictionless %.4f J), energy at 10 s "
          "%.3f to %.3f of the frictionless run's\n",
          toString(integrator).c_str(), mu, rise, frictionless_rise, lowest_ratio, worst_ratio);
      EXPECT_LE(rise, frictionless_rise) << toString(integrator) << " mu " << mu;
    }
  }
}

// ------------------------------------------------------------------------------------------------
// 4. A tilted rod dropped with spin (mu = 0.5). Friction pushes the end that lands against its slip, and
// the energy at 10 s is below the frictionless run's. Its horizontal speed need not end lower: an end that
// sticks turns the fall (8.85 m/s) into a swing about it, which throws the rod sideways (a rod stuck at
// 45 degrees leaves at 3/4 v cos 45 sin 45 = 3.3 m/s horizontally even without the springs' rebound), and
// a spin can be turned into a slide. Only a rod that lands flat, without spin, just loses its slide.

TEST(RodFriction, TiltedSpinningDropIsPushedAgainstItsSlip) {
  for (Integrator integrator : kIntegrators) {
    for (double theta0 : {0.3, 1.0, 2.5}) {
      for (double omega0 : {-6.0, 6.0}) {
        const RodMotion start{0.0, 4.0, theta0, 2.0, 0.0, omega0};
        const RodParams p0 = frictionParams(integrator, 0.0), p = frictionParams(integrator, 0.5);
        RodMotion frictionless = start, s = start;
        bool touched = false;
        for (int n = 0; n < 10000; ++n) {
          const int lower = endHeight(p, s, 1) < endHeight(p, s, -1) ? 1 : -1;
          if (!touched && endHeight(p, s, lower) < 0.0) {  // the first step in contact: one end, the lower
            touched = true;
            const RodMotion without = stepOf(p0, s, kTextDt), with = stepOf(p, s, kTextDt);
            const double slip = endSlip(p, s, lower);
            std::printf(
                "[ landing] %-15s theta0 %.1f omega0 %+.0f: end %c lands slipping at %+.3f m/s, friction "
                "changes vx by %+.2e m/s in its first step\n",
                toString(integrator).c_str(), theta0, omega0, lower == 1 ? 'A' : 'B', slip,
                with.vx - without.vx);
            EXPECT_LT((with.vx - without.vx) * slip, 0.0) << toString(integrator) << " theta0 " << theta0;
          }
          frictionless = stepOf(p0, frictionless, kTextDt);
          s = stepOf(p, s, kTextDt);
        }
        EXPECT_TRUE(touched);
        std::printf(
            "[ drop   ] %-15s theta0 %.1f omega0 %+.0f: at 10 s vx %+.4f m/s, E %.3f J (frictionless "
            "%+.4f m/s, %.3f J)\n",
            toString(integrator).c_str(), theta0, omega0, s.vx, energyOf(p, s), frictionless.vx,
            energyOf(p0, frictionless));
        EXPECT_EQ(frictionless.vx, 2.0);  // the frictionless floor never touches vx
        EXPECT_LT(energyOf(p, s), energyOf(p0, frictionless)) << toString(integrator) << " theta0 " << theta0;
      }
    }
    // Landing flat without spin: the slide (vx = 2 m/s, 1 J) is gone within the first contact, whose normal
    // impulse (2 M sqrt(2 g h0) = 8.9 N s) bounds a friction impulse 4.4 times the rod's momentum M vx.
    // (Later the flat bounce tips over: it is unstable to tilt, frictionless too, and the rounding-level tilt
    // that sliding leaves grows about a thousandfold every 3 s.)
    Rod flat(frictionParams(integrator, 0.5), RodMotion{0.0, 4.0, 0.0, 2.0, 0.0, 0.0});
    while (std::min(flat.endHeightA(), flat.endHeightB()) >= 0.0) flat.step(kTextDt);
    while (std::min(flat.endHeightA(), flat.endHeightB()) < 0.0) flat.step(kTextDt);
    std::printf("[ flat   ] %-15s vx after the first contact %.2e m/s\n", toString(integrator).c_str(),
                flat.state().vx);
    EXPECT_LE(std::fabs(flat.state().vx), 1e-12) << toString(integrator);
  }
}

// The lesson's rod (config/rod.yaml, the text's run) with floor_mu = 0.3, as its comment and docs/rviz.md
// say: the slide ends within a few bounces, the rod staying within half a metre of where it is at 12 s to
// the end of a minute (on the text's floor it slides 96 m in that time).
TEST(RodFriction, TheLessonsRodStopsSlidingOnARoughFloor) {
  WorldConfig config = loadWorldConfigFile(test::config("rod.yaml"));
  RodConfig& rod = std::get<RodConfig>(config.bodies.at(0).config);
  ASSERT_EQ(rod.params.floor_mu, 0.0) << "the text's floor by default";
  rod.params.floor_mu = 0.3;
  World world(config);
  const auto x = [&] { return std::get<Rod>(world.bodies().at(0).model).state().x; };
  while (world.time() < 12.0) world.step();
  const double x12 = x();
  double farthest = 0.0;
  while (world.time() < 60.0) {
    world.step();
    farthest = std::max(farthest, std::fabs(x() - x12));
  }
  std::printf("[ lesson ] x at 12 s %.3f m, farthest from it to 60 s %.3f m\n", x12, farthest);
  EXPECT_LT(farthest, 0.5);
}

}  // namespace
}  // namespace rigid_body_sim
