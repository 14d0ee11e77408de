// Tests of the bouncing rod: the text's program reproduced bit for bit, against the text's own numpy run,
// energy, closed forms, sub-stepping, convergence orders, symmetries and the Rod API.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "rigid_body_sim/core/constants.h"
#include "rigid_body_sim/core/rod.h"
#include "rigid_body_sim/core/rod_dynamics.h"
#include "rod_text_oracle.h"

namespace rigid_body_sim {
namespace {

constexpr double kTextDt = 0.001;
const std::vector<double> kTheta0s = {0.0, 0.3, 1.0, kPi / 2, 2.5, 4.0, 5.5};
const std::vector<Integrator> kIntegrators = {Integrator::EulerCromer, Integrator::VelocityVerlet,
                                              Integrator::Rk4};

RodParams textParams(Integrator integrator = Integrator::EulerCromer) {
  RodParams p;
  p.length = 1.0;
  p.mass = 0.5;
  p.k = 1000.0;
  p.gravity = 9.8;
  p.integrator = integrator;
  return p;
}

RodMotion textInitial(double theta0) { return RodMotion{0.0, 4.0, theta0, 2.0, 0.0, 0.0}; }

std::uint64_t bits(double v) {
  std::uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

double maxAbsDiff(const RodMotion& a, const RodMotion& b) {
  return std::max({std::fabs(a.x - b.x), std::fabs(a.y - b.y), std::fabs(a.theta - b.theta),
                   std::fabs(a.vx - b.vx), std::fabs(a.vy - b.vy), std::fabs(a.omega - b.omega)});
}

// Positions only (m and rad), the quantities the text plots.
double maxPositionDiff(const RodMotion& a, double x, double y, double theta) {
  return std::max({std::fabs(a.x - x), std::fabs(a.y - y), std::fabs(a.theta - theta)});
}

// Runs `steps` steps of dt and calls `visit(step_index_after, rod)` after each.
void run(Rod& rod, double dt, int steps, const std::function<void(int, const Rod&)>& visit) {
  for (int i = 1; i <= steps; ++i) {
    rod.step(dt);
    visit(i, rod);
  }
}

// ------------------------------------------------------------------------------------------------
// 1. The core's Euler-Cromer is the text's program: every bit of every sample for 10 s.

TEST(RodTextProgram, EulerCromerEqualsTranscriptionBitForBit) {
  for (double theta0 : kTheta0s) {
    const std::vector<rbs_test::OracleSample> text = rbs_test::runTextProgram(theta0);
    ASSERT_EQ(text.size(), 10000u);
    Rod rod(textParams(), textInitial(theta0));
    ASSERT_EQ(rod.substepsFor(kTextDt), 1);
    double lowest_end = 1e9;
    for (std::size_t i = 0; i < text.size(); ++i) {
      const RodMotion& s = rod.state();
      const rbs_test::OracleSample& o = text[i];
      const bool same = bits(s.x) == bits(o.x) && bits(s.y) == bits(o.y) && bits(s.theta) == bits(o.theta) &&
                        bits(s.vx) == bits(o.vx) && bits(s.vy) == bits(o.vy) &&
                        bits(s.omega) == bits(o.omega);
      ASSERT_TRUE(same) << "theta0 " << theta0 << " sample " << i << ": rod (" << s.x << ", " << s.y << ", "
                        << s.theta << ", " << s.vx << ", " << s.vy << ", " << s.omega << ") text (" << o.x
                        << ", " << o.y << ", " << o.theta << ", " << o.vx << ", " << o.vy << ", " << o.omega
                        << ")";
      lowest_end = std::min({lowest_end, rod.endHeightA(), rod.endHeightB()});
      rod.step(kTextDt);
    }
    // The comparison covers bounces, not just flight.
    EXPECT_LT(lowest_end, -0.02) << "theta0 " << theta0;
  }
}

// substeps: 1 is the text's scheme at any k: bit for bit with the text's program at floors stiff enough for
// auto to split the steps (omega_c dt = 0.2, 0.4, 0.63), where the text's program is still stable.
TEST(RodTextProgram, SubstepsOneEqualsTranscriptionAtStifferFloors) {
  for (double k : {5000.0, 20000.0, 50000.0}) {
    RodParams params = textParams();
    params.k = k;
    ASSERT_GT(Rod(params, textInitial(0.3)).substepsFor(kTextDt), 1) << "auto splits at k " << k;
    params.substeps = 1;
    rbs_test::TextParams text_params;
    text_params.k = k;
    for (double theta0 : {0.0, 0.3, 2.5}) {
      const std::vector<rbs_test::OracleSample> text = rbs_test::runTextProgram(theta0, -1, text_params);
      ASSERT_EQ(text.size(), 10000u);
      Rod rod(params, textInitial(theta0));
      ASSERT_EQ(rod.substepsFor(kTextDt), 1);
      for (std::size_t i = 0; i < text.size(); ++i) {
        const RodMotion& s = rod.state();
        const rbs_test::OracleSample& o = text[i];
        ASSERT_TRUE(bits(s.x) == bits(o.x) && bits(s.y) == bits(o.y) && bits(s.theta) == bits(o.theta) &&
                    bits(s.vx) == bits(o.vx) && bits(s.vy) == bits(o.vy) && bits(s.omega) == bits(o.omega))
            << "k " << k << " theta0 " << theta0 << " sample " << i;
        rod.step(kTextDt);
      }
    }
  }
}

// ------------------------------------------------------------------------------------------------
// 2. Against the text's program run by numpy (test/data/text_program_reference.py).

struct CsvRow {
  int i;
  double t, x, y, theta, vx, vy, omega;
};

std::map<double, std::vector<CsvRow>> readReference(const std::string& path) {
  std::map<double, std::vector<CsvRow>> by_theta0;
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string f[9];
    for (std::string& v : f) std::getline(fields, v, ',');
    const double theta0 = std::strtod(f[0].c_str(), nullptr);
    by_theta0[theta0].push_back({std::stoi(f[1]), std::strtod(f[2].c_str(), nullptr),
                                 std::strtod(f[3].c_str(), nullptr), std::strtod(f[4].c_str(), nullptr),
                                 std::strtod(f[5].c_str(), nullptr), std::strtod(f[6].c_str(), nullptr),
                                 std::strtod(f[7].c_str(), nullptr), std::strtod(f[8].c_str(), nullptr)});
  }
  return by_theta0;
}

TEST(RodTextProgram, AgreesWithNumpyRunOfTheText) {
  const auto reference = readReference(std::string(RBS_TEST_DATA_DIR) + "/text_program_reference.csv");
  ASSERT_EQ(reference.size(), kTheta0s.size()) << "missing or incomplete reference CSV";
  for (const auto& [theta0, rows] : reference) {
    ASSERT_EQ(rows.back().i, 9999) << "theta0 " << theta0;
    Rod rod(textParams(), textInitial(theta0));
    int step = 0;
    double max_3s = 0.0, max_10s = 0.0;
    int first_diff = -1;
    for (const CsvRow& row : rows) {
      for (; step < row.i; ++step) rod.step(kTextDt);
      const RodMotion& s = rod.state();
      const double d = maxPositionDiff(s, row.x, row.y, row.theta);
      if (d != 0.0 && first_diff < 0) first_diff = row.i;
      if (row.i <= 3000) max_3s = std::max(max_3s, d);
      max_10s = std::max(max_10s, d);
      EXPECT_EQ(bits(s.vx), bits(row.vx)) << "vx is constant in both; theta0 " << theta0;
    }
    std::printf(
        "[ numpy  ] theta0 %-9.6g first differing sample %5d, max |dx,dy,dtheta| 3 s: %.3g, "
        "10 s: %.3g\n",
        theta0, first_diff, max_3s, max_10s);
    EXPECT_LE(max_3s, 1e-9) << "theta0 " << theta0;
    // Over the whole 10 s the bounces amplify the last bits in which numpy's sin and cos and the C library's
    // differ (the text's operations in C++ are equal bit for bit: section 1): at most 1e-3 m or rad
    // (4.4e-4 measured, at theta0 = 1), as README.md says.
    EXPECT_LE(max_10s, 1e-3) << "theta0 " << theta0;
  }
}

// ------------------------------------------------------------------------------------------------
// 3. Energy of the text's rod stays bounded: Euler-Cromer is symplectic, so it oscillates, not drifts.

// Largest |E - E0| / E0 over `steps` steps, over all samples and over samples with both ends in the air.
struct EnergySwing {
  double all = 0.0;
  double in_flight = 0.0;
};
EnergySwing energySwing(Rod& rod, double dt, int steps) {
  const double e0 = rod.energy();
  EnergySwing swing;
  run(rod, dt, steps, [&](int, const Rod& r) {
    const double rel = std::fabs(r.energy() - e0) / e0;
    EXPECT_TRUE(std::isfinite(rel));
    swing.all = std::max(swing.all, rel);
    if (r.endHeightA() >= 0.0 && r.endHeightB() >= 0.0) swing.in_flight = std::max(swing.in_flight, rel);
  });
  return swing;
}

TEST(RodEnergy, TextRodEnergyStaysBoundedFor10s) {
  for (Integrator integrator : kIntegrators) {
    for (double theta0 : kTheta0s) {
      Rod rod(textParams(integrator), textInitial(theta0));
      const EnergySwing swing = energySwing(rod, kTextDt, 9999);
      std::printf("[ energy ] %-15s theta0 %-9.6g max |dE|/E0 %.4f, in flight %.5f\n",
                  toString(integrator).c_str(), theta0, swing.all, swing.in_flight);
      // Measured maxima over these theta0: Euler-Cromer 4.2 % (inside contacts: the O(w dt) swing of its
      // modified energy) and 0.41 % in flight; Verlet 0.30 % / 0.17 %; RK4 0.12 % / 0.12 %.
      const bool ec = integrator == Integrator::EulerCromer;
      EXPECT_LT(swing.all, ec ? 0.06 : 0.005) << toString(integrator) << " theta0 " << theta0;
      EXPECT_LT(swing.in_flight, ec ? 0.01 : 0.003) << toString(integrator) << " theta0 " << theta0;
    }
  }
}

// ------------------------------------------------------------------------------------------------
// 4. Free flight: the centre follows the parabola and theta = theta0 + omega0 t.

TEST(RodFreeFlight, ParabolaAndUniformSpin) {
  const RodMotion start{0.5, 1000.0, 0.7, 2.0, 5.0, 3.0};  // 10 s of falling keeps it far above the floor
  const double g = 9.8, dt = kTextDt;
  const int steps = 10000;
  for (Integrator integrator : kIntegrators) {
    Rod rod(textParams(integrator), start);
    double max_dy = 0.0, max_dx = 0.0, max_dtheta = 0.0, max_dvy = 0.0, max_dy_discrete = 0.0;
    run(rod, dt, steps, [&](int n, const Rod& r) {
      const RodMotion& s = r.state();
      const double t = n * dt;
      ASSERT_GT(std::min(r.endHeightA(), r.endHeightB()), 0.0);
      EXPECT_EQ(s.vx, start.vx);        // no horizontal force, not even rounding
      EXPECT_EQ(s.omega, start.omega);  // no torque in flight
      max_dx = std::max(max_dx, std::fabs(s.x - (start.x + start.vx * t)));
      max_dy = std::max(max_dy, std::fabs(s.y - (start.y + start.vy * t - 0.5 * g * t * t)));
      max_dvy = std::max(max_dvy, std::fabs(s.vy - (start.vy - g * t)));
      max_dtheta = std::max(max_dtheta, std::fabs(s.theta - (start.theta + start.omega * t)));
      // Euler-Cromer's own closed form: y_n = y0 + vy0 t_n - g dt^2 n (n + 1) / 2.
      const double y_ec = start.y + start.vy * t - 0.5 * g * dt * dt * n * (n + 1.0);
      max_dy_discrete = std::max(max_dy_discrete, std::fabs(s.y - y_ec));
    });
    std::printf(
        "[ flight ] %-15s max error x %.2e, y %.2e, vy %.2e, theta %.2e; y vs EC closed "
        "form %.2e\n",
        toString(integrator).c_str(), max_dx, max_dy, max_dvy, max_dtheta, max_dy_discrete);
    EXPECT_LT(max_dx, 1e-10);
    EXPECT_LT(max_dtheta, 1e-10);
    EXPECT_LT(max_dvy, 1e-10);  // velocities are exact for every scheme under constant gravity
    if (integrator == Integrator::EulerCromer) {
      // First order: y lags the parabola by g t dt / 2 exactly (0.049 m at 10 s), no more, no less.
      EXPECT_NEAR(max_dy, 0.5 * g * (steps * dt) * dt, 1e-8);
      EXPECT_LT(max_dy_discrete, 1e-9);
    } else {
      EXPECT_LT(max_dy, 1e-9);  // a quadratic is integrated exactly; only rounding remains
    }
  }
}

// ------------------------------------------------------------------------------------------------
// 5. Sub-stepping keeps very stiff floors stable.

int expectedSubsteps(double k, double mass, double dt) {
  const double ratio = std::sqrt(4.0 * k / mass) * dt;  // omega_c dt
  return ratio > 2.0 * Rod::kSubstepFraction
             ? static_cast<int>(std::ceil(ratio / (2.0 * Rod::kSubstepFraction)))
             : 1;
}

TEST(RodSubstepping, SubstepCounts) {
  Rod rod(textParams(), textInitial(0.3));
  EXPECT_EQ(rod.substepsFor(kTextDt), 1);  // omega_c dt = 0.089 at the text's values
  for (double k : {1e4, 1e5, 1e6, 1e8, 1e9}) {
    RodParams p = textParams();
    p.k = k;
    rod.setParams(p);
    EXPECT_EQ(rod.substepsFor(kTextDt), expectedSubsteps(k, p.mass, kTextDt)) << "k " << k;
  }
  RodParams p = textParams();
  p.k = 1e8;
  rod.setParams(p);
  EXPECT_EQ(rod.substepsFor(kTextDt), 283);  // 28.28 / 0.1 = 282.8
  p.k = 1e9;
  rod.setParams(p);
  EXPECT_EQ(rod.substepsFor(kTextDt), 895);  // 89.44 / 0.1 = 894.4
  // The threshold itself: omega_c dt = 0.1 exactly needs no split, just above it does.
  p.k = 0.5 * 0.1 * 0.1 / 4.0 / (kTextDt * kTextDt);  // omega_c = 100 / s
  rod.setParams(p);
  EXPECT_EQ(rod.substepsFor(kTextDt * 0.999), 1);
  EXPECT_EQ(rod.substepsFor(kTextDt * 1.001), 2);
}

TEST(RodSubstepping, AFixedCountIsKeptWhateverK) {
  RodParams p = textParams();
  for (int n : {1, 2, 7}) {
    p.substeps = n;
    for (double k : {1.0, 1000.0, 1e6}) {
      p.k = k;
      EXPECT_EQ(Rod(p, textInitial(0.3)).substepsFor(kTextDt), n) << "k " << k;
    }
  }
  // Two sub-steps of dt / 2 are two steps of dt / 2 (dt / 2 exact in binary).
  p.k = 5000.0;
  p.substeps = 2;
  Rod split(p, textInitial(0.3));
  p.substeps = 1;
  Rod halves(p, textInitial(0.3));
  for (int i = 0; i < 3000; ++i) {
    split.step(kTextDt);
    halves.step(kTextDt / 2);
    halves.step(kTextDt / 2);
  }
  EXPECT_EQ(maxAbsDiff(split.state(), halves.state()), 0.0);
}

TEST(RodSubstepping, SubstepsTextIsAutoOrAWholeNumber) {
  EXPECT_EQ(substepsFromString("auto"), kAutoSubsteps);
  EXPECT_EQ(substepsFromString("1"), 1);
  EXPECT_EQ(substepsFromString("1000000000"), kMaxSubsteps);
  for (const char* bad : {"", "0", "-1", "1.5", "2e3", " 2", "two", "Auto", "1000000001", "99999999999"}) {
    EXPECT_EQ(substepsFromString(bad), std::nullopt) << "'" << bad << "'";
  }
  EXPECT_EQ(substepsToString(kAutoSubsteps), "auto");
  EXPECT_EQ(substepsToString(12), "12");
}

TEST(RodSubstepping, StiffFloorStaysFiniteAndConservesEnergy) {
  struct Case {
    double k;
    Integrator integrator;
  };
  for (const Case c : {Case{1e8, Integrator::EulerCromer}, Case{1e9, Integrator::EulerCromer},
                       Case{1e8, Integrator::VelocityVerlet}, Case{1e8, Integrator::Rk4}}) {
    RodParams p = textParams(c.integrator);
    p.k = c.k;
    Rod rod(p, textInitial(0.3));
    ASSERT_GT(rod.substepsFor(kTextDt), 1);
    const EnergySwing swing = energySwing(rod, kTextDt, 10000);
    const RodMotion& s = rod.state();
    ASSERT_TRUE(std::isfinite(s.x) && std::isfinite(s.y) && std::isfinite(s.theta) && std::isfinite(s.vx) &&
                std::isfinite(s.vy) && std::isfinite(s.omega));
    std::printf("[ stiff  ] k %.0e %-15s %d substeps: max |dE|/E0 %.4f, in flight %.4f\n", c.k,
                toString(c.integrator).c_str(), rod.substepsFor(kTextDt), swing.all, swing.in_flight);
    // Within 5 % at every sample. Inside a contact Euler-Cromer's energy swings by up to omega h / 2
    // of the contact energy: 5 % at omega_c h = 2 kSubstepFraction = 0.1.
    EXPECT_LT(swing.in_flight, 0.05) << "k " << c.k << " " << toString(c.integrator);
    EXPECT_LT(swing.all, 0.05) << "k " << c.k << " " << toString(c.integrator);
  }
}

// Without sub-steps the same stiff drop is unstable: the guard above is what keeps it sane.
TEST(RodSubstepping, WithoutSubstepsStiffFloorBlowsUp) {
  RodParams p = textParams();
  p.k = 1e8;
  RodMotion s = textInitial(0.3);
  const double e0 = Rod(p, s).energy();
  Rod probe(p, s);
  for (int i = 0; i < 2000; ++i) s = eulerCromerStep(p, s, kTextDt);
  probe.setInitial(s);
  EXPECT_FALSE(std::isfinite(probe.energy()) && probe.energy() < 2.0 * e0);
}

// ------------------------------------------------------------------------------------------------
// 6. Convergence orders on a smooth contact problem: a nearly flat rod pressed into the floor, both
// ends always below it, so the force is linear in y and smooth in theta (no contact switching).

RodMotion pressedRod() { return RodMotion{0.0, -0.004, 0.001, 0.3, 0.0, 0.0}; }

using StepFn = RodMotion (*)(const RodParams&, const RodMotion&, double);

// Trajectory sampled every `every` steps of dt, `samples` samples after the start.
std::vector<RodMotion> trajectory(StepFn step, const RodParams& p, RodMotion s, double dt, int every,
                                  int samples) {
  std::vector<RodMotion> out;
  for (int n = 0; n < samples; ++n) {
    for (int i = 0; i < every; ++i) s = step(p, s, dt);
    out.push_back(s);
  }
  return out;
}

double maxPositionError(const std::vector<RodMotion>& a, const std::vector<RodMotion>& b) {
  double e = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    e = std::max(e, maxPositionDiff(a[i], b[i].x, b[i].y, b[i].theta));
  return e;
}

TEST(RodConvergence, ObservedOrdersOnSmoothContact) {
  const RodParams p = textParams();
  const double every = 2e-3;  // compare every 2 ms
  const int samples = 100;    // for 0.2 s, about two rocking periods (omega = sqrt(6 k / M) = 110 / s)
  const std::vector<RodMotion> ref = trajectory(rk4Step, p, pressedRod(), every / 64, 64, samples);
  for (const RodMotion& s : ref) {  // the premise: both ends stay in contact throughout
    ASSERT_LT(s.y + 0.5 * std::fabs(std::sin(s.theta)), 0.0);
  }
  // Euler-Cromer's error is an O(h) bounded offset plus an O(h^2) phase drift that grows like
  // t omega (omega h)^2 / 24; its coarsest step is small enough for the O(h) part to dominate.
  // RK4's is large enough that its finest error stays far above rounding.
  struct Scheme {
    StepFn step;
    const char* name;
    int steps_per_sample;  // at the coarsest of the three step sizes
    double order;
    double band;
  };
  for (const Scheme sc :
       {Scheme{eulerCromerStep, "euler_cromer", 8, 1.0, 0.2},
        Scheme{velocityVerletStep, "velocity_verlet", 1, 2.0, 0.2}, Scheme{rk4Step, "rk4", 1, 4.0, 0.4}}) {
    double err[3];
    for (int j = 0; j < 3; ++j) {
      const int per_sample = sc.steps_per_sample << j;
      err[j] = maxPositionError(trajectory(sc.step, p, pressedRod(), every / per_sample, per_sample, samples),
                                ref);
    }
    const double p1 = std::log2(err[0] / err[1]);
    const double p2 = std::log2(err[1] / err[2]);
    std::printf("[ order  ] %-15s dt %.3g: errors %.3e %.3e %.3e, observed orders %.3f %.3f\n", sc.name,
                every / sc.steps_per_sample, err[0], err[1], err[2], p1, p2);
    EXPECT_NEAR(p1, sc.order, sc.band) << sc.name;
    EXPECT_NEAR(p2, sc.order, sc.band) << sc.name;
    EXPECT_GT(err[2], 1e-12) << sc.name << ": finest error at rounding level, orders meaningless";
  }
}

// ------------------------------------------------------------------------------------------------
// 7. The integrators agree on the first bounce of a tilted drop: contact time and deepest penetration.

struct FirstBounce {
  double contact_time = -1.0;  // first sample with an end below the floor
  double depth = 0.0;          // deepest end below the floor until both ends are up again
};
FirstBounce firstBounce(Integrator integrator, double theta0, double dt) {
  Rod rod(textParams(integrator), textInitial(theta0));
  FirstBounce b;
  for (int n = 1; n < static_cast<int>(3.0 / dt); ++n) {
    rod.step(dt);
    const double lowest = std::min(rod.endHeightA(), rod.endHeightB());
    if (lowest < 0.0 && b.contact_time < 0.0) b.contact_time = n * dt;
    if (b.contact_time < 0.0) continue;
    if (lowest >= 0.0) break;  // left the floor
    b.depth = std::max(b.depth, -lowest);
  }
  return b;
}

TEST(RodIntegratorsAgree, FirstContactOfTiltedDrop) {
  const double g = 9.8, dt = kTextDt;
  for (double theta0 : {0.3, 1.0, 2.5, 4.0}) {
    // Flight is a parabola with theta fixed: the lower end reaches the floor at t_c.
    const double t_c = std::sqrt(2.0 * (4.0 - 0.5 * std::fabs(std::sin(theta0))) / g);
    const FirstBounce fine = firstBounce(Integrator::Rk4, theta0, dt / 100);
    EXPECT_NEAR(fine.contact_time, t_c, dt / 100);
    for (Integrator integrator : kIntegrators) {
      const FirstBounce b = firstBounce(integrator, theta0, dt);
      std::printf(
          "[ bounce ] theta0 %-4g %-15s contact at %.4f s (exact %.5f), depth %.5f m (fine RK4 "
          "%.5f)\n",
          theta0, toString(integrator).c_str(), b.contact_time, t_c, b.depth, fine.depth);
      if (integrator == Integrator::EulerCromer) {
        EXPECT_NEAR(b.contact_time, t_c, dt);  // it falls g t dt / 2 ahead, half a step early
      } else {
        EXPECT_GT(b.contact_time, t_c);  // exact parabola: the first sample past t_c
        EXPECT_LE(b.contact_time, t_c + dt + 1e-12) << toString(integrator);
      }
      // Measured within 1.3e-4 m of the fine run; 1 mm is (1 m/s) dt.
      EXPECT_NEAR(b.depth, fine.depth, 1e-3) << toString(integrator);
    }
  }
}

// ------------------------------------------------------------------------------------------------
// 8. Mirror symmetry x -> -x. The mirrored rod is the same segment at angle pi - theta, or equally at
// -theta with ends A and B swapped. -theta, -x, -vx, -omega are exact in floating point and every
// operation of the force model is odd or even in them (glibc's sin is odd and cos even, bit for bit),
// so that form holds exactly for all schemes. pi - theta0 is rounded, and cos(pi - theta0) is not
// bit for bit -cos(theta0): that form holds to rounding, amplified by each tilted bounce.

RodMotion mirrored(const RodMotion& s) { return RodMotion{-s.x, s.y, -s.theta, -s.vx, s.vy, -s.omega}; }

TEST(RodSymmetry, MirrorWithEndsSwappedIsExact) {
  for (Integrator integrator : kIntegrators) {
    for (double theta0 : kTheta0s) {
      Rod rod(textParams(integrator), textInitial(theta0));
      Rod mirror(textParams(integrator), mirrored(textInitial(theta0)));
      for (int n = 0; n < 10000; ++n) {
        const RodMotion m = mirrored(rod.state());
        const RodMotion& s = mirror.state();
        ASSERT_TRUE(s.x == m.x && s.y == m.y && s.theta == m.theta && s.vx == m.vx && s.vy == m.vy &&
                    s.omega == m.omega)
            << toString(integrator) << " theta0 " << theta0 << " step " << n;
        ASSERT_EQ(mirror.endHeightA(), rod.endHeightB());
        rod.step(kTextDt);
        mirror.step(kTextDt);
      }
    }
  }
}

TEST(RodSymmetry, MirrorAsPiMinusThetaHoldsToRounding) {
  for (Integrator integrator : kIntegrators) {
    for (double theta0 : {0.3, 1.0, 2.5, 4.0}) {
      Rod rod(textParams(integrator), textInitial(theta0));
      RodMotion m0 = textInitial(kPi - theta0);
      m0.vx = -m0.vx;
      Rod mirror(textParams(integrator), m0);
      double max_3s = 0.0, max_10s = 0.0;
      for (int n = 1; n < 10000; ++n) {
        rod.step(kTextDt);
        mirror.step(kTextDt);
        const RodMotion& s = rod.state();
        const RodMotion& m = mirror.state();
        EXPECT_EQ(m.x, -s.x);  // vx is untouched by the floor, so x mirrors exactly
        const double d = std::max({std::fabs(m.y - s.y), std::fabs(m.theta - (kPi - s.theta)),
                                   std::fabs(m.omega + s.omega) * kTextDt});
        if (n <= 3000) max_3s = std::max(max_3s, d);
        max_10s = std::max(max_10s, d);
      }
      std::printf("[ mirror ] %-15s theta0 %-4g pi - theta: max |dy|, |dtheta| 3 s %.2e, 10 s %.2e\n",
                  toString(integrator).c_str(), theta0, max_3s, max_10s);
      EXPECT_LT(max_3s, 1e-9) << toString(integrator) << " theta0 " << theta0;
    }
  }
}

// ------------------------------------------------------------------------------------------------
// 9. A flat rod dropped straight: both ends land together and it never turns.

TEST(RodFlatDrop, NoRotationAndEndsTogether) {
  for (Integrator integrator : kIntegrators) {
    Rod rod(textParams(integrator), RodMotion{0.0, 4.0, 0.0, 0.0, 0.0, 0.0});
    int contacts = 0;
    double lowest = 0.0;
    for (int n = 0; n < 10000; ++n) {
      rod.step(kTextDt);
      const RodMotion& s = rod.state();
      ASSERT_EQ(s.omega, 0.0) << toString(integrator) << " step " << n;
      ASSERT_EQ(s.theta, 0.0);
      ASSERT_EQ(s.x, 0.0);
      ASSERT_EQ(rod.endHeightA(), rod.endHeightB());
      if (rod.endHeightA() < 0.0) ++contacts;
      lowest = std::min(lowest, rod.endHeightA());
    }
    EXPECT_GT(contacts, 100) << toString(integrator);  // it did bounce, several times
    // Two springs of k on M: depth ~ v_impact / sqrt(2 k / M) = 8.85 / 63.2 m.
    EXPECT_NEAR(-lowest, std::sqrt(2 * 9.8 * 4.0) / std::sqrt(2 * 1000.0 / 0.5), 0.01);
  }
}

// ------------------------------------------------------------------------------------------------
// 10. The Rod API: parameters mid-run, initial state, reset, integrator names.

TEST(RodApi, SetParamsKeepsStateAndAppliesFromNextStep) {
  Rod rod(textParams(), textInitial(0.3));
  for (int n = 0; n < 700; ++n) rod.step(kTextDt);  // mid-flight
  const RodMotion before = rod.state();
  RodParams stiff = textParams(Integrator::Rk4);
  stiff.k = 5000.0;
  rod.setParams(stiff);
  EXPECT_EQ(maxAbsDiff(rod.state(), before), 0.0);
  EXPECT_EQ(rod.params().k, 5000.0);
  EXPECT_EQ(rod.params().integrator, Integrator::Rk4);
  Rod fresh(stiff, before);  // what the new parameters do from this state
  for (int n = 0; n < 500; ++n) {
    rod.step(kTextDt);
    fresh.step(kTextDt);
  }
  EXPECT_EQ(maxAbsDiff(rod.state(), fresh.state()), 0.0);
  Rod unchanged(textParams(), before);  // and it differs from keeping the old ones (bounce in there)
  for (int n = 0; n < 500; ++n) unchanged.step(kTextDt);
  EXPECT_GT(maxAbsDiff(rod.state(), unchanged.state()), 1e-3);
  EXPECT_EQ(maxAbsDiff(rod.initial(), textInitial(0.3)), 0.0);  // the initial state is untouched
}

TEST(RodApi, SetInitialAndReset) {
  Rod rod(textParams(), textInitial(0.3));
  EXPECT_EQ(maxAbsDiff(rod.state(), textInitial(0.3)), 0.0);
  for (int n = 0; n < 100; ++n) rod.step(kTextDt);
  EXPECT_GT(maxAbsDiff(rod.state(), textInitial(0.3)), 0.1);
  rod.reset();
  EXPECT_EQ(maxAbsDiff(rod.state(), textInitial(0.3)), 0.0);

  const RodMotion other{1.0, 2.0, 3.0, -1.0, 0.5, 2.0};
  for (int n = 0; n < 100; ++n) rod.step(kTextDt);
  rod.setInitial(other);
  EXPECT_EQ(maxAbsDiff(rod.state(), other), 0.0);
  EXPECT_EQ(maxAbsDiff(rod.initial(), other), 0.0);
  for (int n = 0; n < 100; ++n) rod.step(kTextDt);
  rod.reset();
  EXPECT_EQ(maxAbsDiff(rod.state(), other), 0.0);

  // After a reset the run repeats itself exactly.
  Rod again(textParams(), other);
  for (int n = 0; n < 1000; ++n) {
    rod.step(kTextDt);
    again.step(kTextDt);
  }
  EXPECT_EQ(maxAbsDiff(rod.state(), again.state()), 0.0);
}

// ---- a bounded floor: x in [0, floor_length]; leaving it restarts the rod, as a roller's slope end does
// ----

RodParams onFloorOf(double floor_length) {
  RodParams p = textParams();
  p.floor_length = floor_length;
  return p;
}

// The first step after which the centre of an unbounded twin is off [0, floor_length] (1-based), or -1.
int firstStepOff(const RodMotion& initial, double floor_length, int max_steps) {
  Rod twin(textParams(), initial);
  for (int k = 1; k <= max_steps; ++k) {
    twin.step(kTextDt);
    if (twin.state().x < 0.0 || twin.state().x > floor_length) return k;
  }
  return -1;
}

void checkFloorRestarts(const RodMotion& initial, double floor_length) {
  const int k_off = firstStepOff(initial, floor_length, 20000);
  ASSERT_GT(k_off, 1);
  Rod unbounded(textParams(), initial);
  Rod rod(onFloorOf(floor_length), initial);
  for (int lap = 1; lap <= 2; ++lap) {
    unbounded = Rod(textParams(), initial);
    for (int k = 1; k <= k_off; ++k) {
      const bool restarted = rod.step(kTextDt).restarted();
      unbounded.step(kTextDt);
      ASSERT_EQ(restarted, k == k_off) << "lap " << lap << " k = " << k;
      // On the floor the run is the unbounded one, bit for bit.
      if (k < k_off)
        ASSERT_EQ(maxAbsDiff(rod.state(), unbounded.state()), 0.0) << "lap " << lap << " k = " << k;
    }
    EXPECT_EQ(maxAbsDiff(rod.state(), initial), 0.0) << "lap " << lap << ": not back at its initial state";
  }
}

TEST(RodFloor, UnboundedIsTheTextsFloor) {
  Rod text(textParams(), textInitial(0.3));
  Rod unbounded(onFloorOf(0.0), textInitial(0.3));
  for (int n = 0; n < 10000; ++n) {
    EXPECT_FALSE(unbounded.step(kTextDt).restarted());
    text.step(kTextDt);
  }
  EXPECT_EQ(maxAbsDiff(unbounded.state(), text.state()), 0.0);
  EXPECT_GT(unbounded.state().x, 15.0);  // far beyond any floor a demo would give it
}

TEST(RodFloor, RunningPastTheFarEndRestarts) { checkFloorRestarts(textInitial(0.3), 5.0); }

TEST(RodFloor, RunningPastTheNearEndRestarts) {
  checkFloorRestarts(RodMotion{2.0, 4.0, 1.0, -1.5, 0.0, 3.0}, 5.0);
}

TEST(RodFloor, BothEndsOfTheFloorAreOnIt) {
  // Dropped flat without horizontal motion, the centre stays exactly where it is, bounce after bounce.
  for (const double x0 : {0.0, 5.0}) {
    Rod rod(onFloorOf(5.0), RodMotion{x0, 2.0, 0.0, 0.0, 0.0, 0.0});
    for (int n = 0; n < 5000; ++n)
      ASSERT_FALSE(rod.step(kTextDt).restarted()) << "x0 = " << x0 << ", step " << n;
    EXPECT_EQ(rod.state().x, x0);
  }
}

TEST(RodApi, DerivedQuantities) {
  RodParams p = textParams();
  p.length = 2.0;
  p.mass = 3.0;
  Rod rod(p, RodMotion{0.0, 0.2, kPi / 6, 1.0, -2.0, 4.0});
  EXPECT_DOUBLE_EQ(rod.momentOfInertia(), 3.0 * 4.0 / 12.0);
  EXPECT_DOUBLE_EQ(rod.endHeightA(), 0.2 + 0.5);
  EXPECT_DOUBLE_EQ(rod.endHeightB(), 0.2 - 0.5);
  // kinetic 0.5*3*5 + 0.5*1*16, gravity 3*9.8*0.2, end B 0.3 below the floor: 0.5*1000*0.09.
  EXPECT_NEAR(rod.energy(), 7.5 + 8.0 + 5.88 + 45.0, 1e-12);
}

TEST(RodApi, IntegratorNames) {
  for (Integrator i : kIntegrators) EXPECT_EQ(integratorFromString(toString(i)), i);
  EXPECT_EQ(toString(Integrator::EulerCromer), "euler_cromer");
  EXPECT_EQ(toString(Integrator::VelocityVerlet), "velocity_verlet");
  EXPECT_EQ(toString(Integrator::Rk4), "rk4");
  for (const char* bad : {"", "RK4", "euler", "verlet", "rk4 ", "euler-cromer"}) {
    EXPECT_FALSE(integratorFromString(bad).has_value()) << bad;
  }
}

}  // namespace
}  // namespace rigid_body_sim
