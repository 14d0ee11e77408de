// Tests of Roller against closed forms written here, independently of the class's own formulas.
//
// Tolerances: the class integrates constant accelerations in closed form, so the only deviation from
// the exact trajectory is floating-point rounding, ~ (steps) * eps ~ 1e4 * 1e-16 = 1e-12 relative
// after 10 s at dt = 1e-3. A relative tolerance of 1e-9 leaves a wide margin over rounding while an
// O(dt) integration error (~1e-3) or a wrong constant would fail it by many orders of magnitude.
// "Relative" is measured against the largest magnitude the quantity has had so far, because rounding
// errors scale with that and a pure relative error is meaningless where a quantity crosses zero.
#include "rigid_body_sim/core/constants.h"
#include "rigid_body_sim/core/roller.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace rigid_body_sim {
namespace {

constexpr double kDt = 1e-3;
constexpr double kRelTol = 1e-9;
constexpr double kG = 9.81;
constexpr double kRadius = 0.125;  // a binary fraction, so omega0 = -v0 / R makes u0 exactly 0
constexpr double kMass = 2.0;
constexpr double kLongSlope = 1e6;  // long enough that no restart happens in 10 s

// ---- Worst errors seen, printed once at the end so the accuracy margin is visible in the log. ----
std::map<std::string, double>& worstErrors() {
  static std::map<std::string, double> worst;
  return worst;
}

class WorstErrorReport : public ::testing::Environment {
 public:
  void TearDown() override {
    for (const auto& [what, err] : worstErrors()) {
      std::printf("[roller] worst relative error %-10s %.3e\n", what.c_str(), err);
    }
  }
};
[[maybe_unused]] ::testing::Environment* const kReport =
    ::testing::AddGlobalTestEnvironment(new WorstErrorReport);

// Expects |actual - expected| <= kRelTol * scale (scale > 0) and records the relative error.
void expectClose(const std::string& what, double actual, double expected, double scale) {
  // Exact agreement passes even where the scale is 0 (a quantity that must stay exactly 0).
  const double rel = actual == expected ? 0.0 : std::abs(actual - expected) / scale;
  double& worst = worstErrors()[what];
  worst = std::max(worst, rel);
  EXPECT_LE(rel, kRelTol) << what << ": actual " << actual << " expected " << expected;
}

// ---- Closed-form physics, written from the text, not taken from the class. ----
struct Slope {
  double phi;
  double c;
  double mu_s;
  double mu_d;
  double rollAccel() const { return kG * std::sin(phi) / (1.0 + c); }
  double rollAlpha() const { return -rollAccel() / kRadius; }
  // sigma = +1: contact point slides downhill; friction -sigma mu_d N on the body.
  double slipAccel(int sigma) const { return kG * (std::sin(phi) - sigma * mu_d * std::cos(phi)); }
  double slipAlpha(int sigma) const { return -sigma * mu_d * kG * std::cos(phi) / (c * kRadius); }
  double slipRate(int sigma) const { return slipAccel(sigma) + slipAlpha(sigma) * kRadius; }
  double normal() const { return kMass * kG * std::cos(phi); }
  double rollFriction() const { return -kMass * kG * std::sin(phi) * c / (1.0 + c); }
};

RollerParams makeParams(Shape shape, const Slope& s, double length = kLongSlope) {
  RollerParams p;
  p.shape = shape;
  p.inertia_factor = s.c;
  p.radius = kRadius;
  p.mass = kMass;
  p.incline_angle = s.phi;
  p.incline_length = length;
  p.mu_s = s.mu_s;
  p.mu_d = s.mu_d;
  p.gravity = kG;
  return p;
}

// One interval of constant accelerations starting at time t0.
struct Phase {
  double t0;
  RollerMotion s0;
  double a;
  double alpha;
  RollerMotion at(double t) const {
    const double h = t - t0;
    return {s0.x + s0.v * h + 0.5 * a * h * h, s0.v + a * h, s0.theta + s0.omega * h + 0.5 * alpha * h * h,
            s0.omega + alpha * h};
  }
};

// A trajectory made of consecutive phases.
struct Piecewise {
  std::vector<Phase> phases;
  RollerMotion at(double t) const {
    const Phase* current = &phases.front();
    for (const Phase& p : phases) {
      if (p.t0 <= t) current = &p;
    }
    return current->at(t);
  }
  // Appends a phase starting at t0 from the state the trajectory has reached there.
  void then(double t0, double a, double alpha, std::optional<double> omega_override = std::nullopt) {
    RollerMotion s = at(t0);
    if (omega_override) s.omega = *omega_override;
    phases.push_back({t0, s, a, alpha});
  }
};

Piecewise startAt(const RollerInitial& in, double a, double alpha) {
  return {{{0.0, RollerMotion{in.x0, in.v0, in.theta0, in.omega0}, a, alpha}}};
}

// Slipping with direction sigma until u = 0, then rolling. Returns the stick time through t_stick.
Piecewise slipThenRoll(const Slope& s, const RollerInitial& in, int sigma, double* t_stick) {
  const double u0 = in.v0 + in.omega0 * kRadius;
  *t_stick = -u0 / s.slipRate(sigma);
  Piecewise traj = startAt(in, s.slipAccel(sigma), s.slipAlpha(sigma));
  const double v_star = traj.at(*t_stick).v;
  traj.then(*t_stick, s.rollAccel(), s.rollAlpha(), -v_star / kRadius);
  return traj;
}

// What one run of steps saw, besides the state comparison.
struct StepLog {
  double t;
  RollMode mode;
  double u;
  double friction;
  RollerStepEvents events;
};

struct RunLog {
  std::vector<StepLog> steps;
  std::vector<double> stick_times;  // absolute times: step start + stuck_at
  int restarts = 0;
  int started_slipping = 0;
};

// Steps from step index k_begin to k_end (t = k dt) comparing the state with the closed form.
RunLog runAndCompare(Roller& roller, const Piecewise& expected, int k_begin, int k_end) {
  RunLog log;
  const RollerMotion start = expected.at(k_begin * kDt);
  RollerMotion scale = {std::abs(start.x), std::abs(start.v), std::abs(start.theta), std::abs(start.omega)};
  for (int k = k_begin + 1; k <= k_end; ++k) {
    const RollerStepEvents ev = roller.step(kDt);
    const double t = k * kDt;
    const RollerMotion want = expected.at(t);
    const RollerMotion& got = roller.state();
    scale.x = std::max(scale.x, std::abs(want.x));
    scale.v = std::max(scale.v, std::abs(want.v));
    scale.theta = std::max(scale.theta, std::abs(want.theta));
    scale.omega = std::max(scale.omega, std::abs(want.omega));
    expectClose("x", got.x, want.x, scale.x);
    expectClose("v", got.v, want.v, scale.v);
    expectClose("theta", got.theta, want.theta, scale.theta);
    expectClose("omega", got.omega, want.omega, scale.omega);
    if (ev.stuck_at) log.stick_times.push_back((k - 1) * kDt + *ev.stuck_at);
    log.restarts += ev.restarted ? 1 : 0;
    log.started_slipping += ev.started_slipping ? 1 : 0;
    log.steps.push_back({t, roller.mode(), roller.slipSpeed(), roller.frictionForce(), ev});
    if (::testing::Test::HasFailure()) break;  // one failing step is enough to read
  }
  return log;
}

// Guards the tests' own premise that an event time is well inside a step.
void assertNotOnStepBoundary(double t) {
  const double steps = t / kDt;
  ASSERT_GT(std::abs(steps - std::round(steps)), 0.01) << "choose another case: t = " << t;
}

struct ShapeCase {
  Shape shape;
  double c;
  double critical_factor;  // tan(phi_c) / mu_s from the text's table: (1 + c) / c
};

const std::vector<ShapeCase>& shapeCases() {
  static const std::vector<ShapeCase> cases = {{Shape::Sphere, 2.0 / 5.0, 3.5},
                                               {Shape::Cylinder, 1.0 / 2.0, 3.0},
                                               {Shape::Ring, 1.0, 2.0},
                                               {Shape::SphericalShell, 2.0 / 3.0, 2.5},
                                               {Shape::Custom, 0.25, 5.0}};
  return cases;
}

// ---- Names and constants ----

TEST(RollerNames, ShapesAndModes) {
  EXPECT_EQ(toString(Shape::Sphere), "sphere");
  EXPECT_EQ(toString(Shape::Cylinder), "cylinder");
  EXPECT_EQ(toString(Shape::Ring), "ring");
  EXPECT_EQ(toString(Shape::SphericalShell), "spherical_shell");
  EXPECT_EQ(toString(Shape::Custom), "custom");
  for (Shape s : {Shape::Sphere, Shape::Cylinder, Shape::Ring, Shape::SphericalShell}) {
    EXPECT_EQ(shapeFromString(toString(s)), s);
  }
  EXPECT_FALSE(shapeFromString("custom").has_value());
  EXPECT_FALSE(shapeFromString("Sphere").has_value());
  EXPECT_FALSE(shapeFromString("").has_value());
  EXPECT_EQ(toString(RollMode::Rolling), "rolling");
  EXPECT_EQ(toString(RollMode::Slipping), "slipping");
}

TEST(RollerNames, InertiaFactors) {
  EXPECT_DOUBLE_EQ(inertiaFactorOf(Shape::Sphere), 0.4);
  EXPECT_DOUBLE_EQ(inertiaFactorOf(Shape::Cylinder), 0.5);
  EXPECT_DOUBLE_EQ(inertiaFactorOf(Shape::Ring), 1.0);
  EXPECT_DOUBLE_EQ(inertiaFactorOf(Shape::SphericalShell), 2.0 / 3.0);
  EXPECT_TRUE(std::isnan(inertiaFactorOf(Shape::Custom)));
}

// ---- 1, 2: rolling from rest ----

TEST(RollerRolling, FromRestMatchesClosedFormForEveryShape) {
  for (const ShapeCase& sc : shapeCases()) {
    SCOPED_TRACE(toString(sc.shape));
    const Slope s{0.349, sc.c, 0.3, 0.2};  // tan(0.349) = 0.36 < 0.3 * 2 (ring, the lowest factor)
    const RollerInitial in{0.0, 0.0, 0.0, 0.0};
    Roller r(makeParams(sc.shape, s), in);
    ASSERT_EQ(r.mode(), RollMode::Rolling);
    expectClose("force", r.frictionForce(), s.rollFriction(), std::abs(s.rollFriction()));
    expectClose("force", r.normalForce(), s.normal(), s.normal());
    expectClose("accel", r.acceleration(), s.rollAccel(), s.rollAccel());
    expectClose("accel", r.angularAcceleration(), s.rollAlpha(), std::abs(s.rollAlpha()));

    const RunLog log = runAndCompare(r, startAt(in, s.rollAccel(), s.rollAlpha()), 0, 10000);
    EXPECT_TRUE(log.stick_times.empty());
    EXPECT_EQ(log.restarts, 0);
    EXPECT_EQ(log.started_slipping, 0);
    for (const StepLog& st : log.steps) {
      ASSERT_EQ(st.mode, RollMode::Rolling) << "t = " << st.t;
    }
    // Rolling constraint at the end, and the explicit x(t) = A t^2 / 2 of the text.
    const double t = 10.0;
    const double v = s.rollAccel() * t;
    expectClose("x", r.state().x, 0.5 * s.rollAccel() * t * t, 0.5 * s.rollAccel() * t * t);
    expectClose("omega", r.state().omega, -v / kRadius, v / kRadius);
    expectClose("force", r.frictionForce(), s.rollFriction(), std::abs(s.rollFriction()));
    EXPECT_EQ(r.laps(), 0);
  }
}

TEST(RollerRolling, EnergyIsConserved) {
  for (const ShapeCase& sc : shapeCases()) {
    SCOPED_TRACE(toString(sc.shape));
    const Slope s{0.349, sc.c, 0.3, 0.2};
    // energy() itself, at a state where every term is nonzero.
    const RollerInitial moving{2.0, 1.5, 0.0, 3.0};
    const double e_moving = 0.5 * kMass * 1.5 * 1.5 + 0.5 * sc.c * kMass * kRadius * kRadius * 3.0 * 3.0 -
                            kMass * kG * 2.0 * std::sin(s.phi);
    expectClose("energy", Roller(makeParams(sc.shape, s), moving).energy(), e_moving, std::abs(e_moving));
    // Released at x = 0, so the potential term never dwarfs the kinetic scale the check is relative to.
    Roller r(makeParams(sc.shape, s), RollerInitial{0.0, 0.0, 0.0, 0.0});
    const double e0 = r.energy();
    EXPECT_EQ(e0, 0.0);
    for (int k = 1; k <= 10000; ++k) {
      r.step(kDt);
      // Kinetic energy of the exact motion: (1 + c) M v^2 / 2 with v = A t.
      const double v = s.rollAccel() * k * kDt;
      const double kinetic = 0.5 * (1.0 + sc.c) * kMass * v * v;
      expectClose("energy", r.energy(), e0, kinetic);
      if (HasFailure()) break;
    }
  }
}

// ---- 3: critical angle from both sides ----

TEST(RollerCritical, RollsJustBelowAndSlipsJustAbove) {
  const double mu_s = 0.3;
  const double mu_d = 0.2;
  for (const ShapeCase& sc : shapeCases()) {
    SCOPED_TRACE(toString(sc.shape));
    const double phi_c = std::atan(sc.critical_factor * mu_s);  // the text's table
    const RollerInitial rest{0.0, 0.0, 0.0, 0.0};

    const Slope below{phi_c * (1.0 - 1e-6), sc.c, mu_s, mu_d};
    EXPECT_TRUE(Roller::canRoll(makeParams(sc.shape, below)));
    Roller rolling(makeParams(sc.shape, below), rest);
    ASSERT_EQ(rolling.mode(), RollMode::Rolling);
    const RunLog roll_log =
        runAndCompare(rolling, startAt(rest, below.rollAccel(), below.rollAlpha()), 0, 10000);
    for (const StepLog& st : roll_log.steps) ASSERT_EQ(st.mode, RollMode::Rolling) << "t = " << st.t;
    EXPECT_EQ(roll_log.started_slipping, 0);

    const Slope above{phi_c * (1.0 + 1e-6), sc.c, mu_s, mu_d};
    EXPECT_FALSE(Roller::canRoll(makeParams(sc.shape, above)));
    Roller slipping(makeParams(sc.shape, above), rest);
    ASSERT_EQ(slipping.mode(), RollMode::Slipping);
    expectClose("accel", slipping.acceleration(), above.slipAccel(+1), above.slipAccel(+1));
    expectClose("accel", slipping.angularAcceleration(), above.slipAlpha(+1), std::abs(above.slipAlpha(+1)));
    expectClose("force", slipping.frictionForce(), -mu_d * above.normal(), mu_d * above.normal());
    const RunLog slip_log =
        runAndCompare(slipping, startAt(rest, above.slipAccel(+1), above.slipAlpha(+1)), 0, 10000);
    EXPECT_TRUE(slip_log.stick_times.empty());
    for (const StepLog& st : slip_log.steps) {
      ASSERT_EQ(st.mode, RollMode::Slipping) << "t = " << st.t;
      ASSERT_GT(st.u, 0.0) << "t = " << st.t;
    }
  }
}

// The critical angle against the text's table, tan(phi_c) = mu_s (1 + c) / c, and against physics.md's
// degrees for mu_s = 0.2 (35.0, 31.0, 21.8, 26.6 and, for c = 1/4, atan(1.0) = 45).
TEST(RollerCritical, AngleIsTheClosedForm) {
  const std::vector<double> degrees_at_02 = {35.0, 31.0, 21.8, 26.6, 45.0};
  for (std::size_t i = 0; i < shapeCases().size(); ++i) {
    const ShapeCase& sc = shapeCases()[i];
    SCOPED_TRACE(toString(sc.shape));
    const double c = sc.shape == Shape::Custom ? sc.c : inertiaFactorOf(sc.shape);
    for (const double mu_s : {0.05, 0.2, 0.3, 1.0}) {
      EXPECT_DOUBLE_EQ(criticalTangent(mu_s, c), sc.critical_factor * mu_s);
      EXPECT_DOUBLE_EQ(criticalAngle(mu_s, c), std::atan(sc.critical_factor * mu_s));
    }
    EXPECT_NEAR(criticalAngle(0.2, c) * 180.0 / kPi, degrees_at_02[i], 0.05);
  }
}

// ---- 4, 5, 6: slip-to-roll transitions ----

// Runs a launch that slips with direction sigma, sticks at the closed-form time, then rolls.
void checkSlipThenRoll(const Slope& s, const RollerInitial& in, int sigma) {
  double t_stick = 0.0;
  const Piecewise traj = slipThenRoll(s, in, sigma, &t_stick);
  ASSERT_GT(t_stick, 0.0);
  assertNotOnStepBoundary(t_stick);
  Roller r(makeParams(Shape::Sphere, s), in);
  ASSERT_EQ(r.mode(), RollMode::Slipping);
  // Kinetic friction opposes the sliding of the contact point: sign -sigma.
  expectClose("force", r.frictionForce(), -sigma * s.mu_d * s.normal(), s.mu_d * s.normal());

  const RunLog log = runAndCompare(r, traj, 0, 10000);
  ASSERT_EQ(log.stick_times.size(), 1u);
  expectClose("t_stick", log.stick_times[0], t_stick, t_stick);
  const double v_scale = std::abs(in.v0) + std::abs(in.omega0) * kRadius + s.rollAccel() * 10.0;
  for (const StepLog& st : log.steps) {
    if (st.t < t_stick) {
      ASSERT_EQ(st.mode, RollMode::Slipping) << "t = " << st.t;
      ASSERT_EQ(st.u > 0.0 ? 1 : -1, sigma) << "t = " << st.t;
    } else {
      ASSERT_EQ(st.mode, RollMode::Rolling) << "t = " << st.t;
      expectClose("u", st.u, 0.0, v_scale);
      expectClose("force", st.friction, s.rollFriction(), std::abs(s.rollFriction()));
    }
  }
}

TEST(RollerTransition, LaunchedSlidingWithoutSpinSticksThenRolls) {
  checkSlipThenRoll(Slope{0.349, 0.4, 0.3, 0.2}, RollerInitial{1.0, 3.0, 0.0, 0.0}, +1);
}

TEST(RollerTransition, BackspinSticksLaterThenRolls) {
  checkSlipThenRoll(Slope{0.349, 0.4, 0.3, 0.2}, RollerInitial{1.0, 3.0, 0.3, 20.0}, +1);
}

TEST(RollerTransition, TopspinIsPushedDownhillThenRolls) {
  // u0 = 1 - 40 * 0.125 = -4 < 0: friction pushes the body downhill until u = 0.
  const Slope s{0.349, 0.4, 0.3, 0.2};
  const RollerInitial in{1.0, 1.0, 0.0, -40.0};
  Roller r(makeParams(Shape::Sphere, s), in);
  EXPECT_GT(r.frictionForce(), 0.0);
  EXPECT_LT(r.slipSpeed(), 0.0);
  checkSlipThenRoll(s, in, -1);
}

TEST(RollerTransition, EnergyLostEqualsFrictionTimesSlipDistance) {
  const Slope s{0.349, 0.4, 0.3, 0.2};
  const RollerInitial in{1.0, 3.0, 0.0, 10.0};
  const double u0 = in.v0 + in.omega0 * kRadius;
  const double rate = s.slipRate(+1);
  const double t_stick = -u0 / rate;
  Roller r(makeParams(Shape::Sphere, s), in);
  const double e0 = r.energy();
  const double energy_scale = 0.5 * kMass * (in.v0 * in.v0 + 0.4 * kRadius * kRadius * in.omega0 * in.omega0);
  for (int k = 1; k <= 5000; ++k) {
    r.step(kDt);
    // Work against kinetic friction: mu_d N times the distance slid, int u dt.
    const double t = std::min(k * kDt, t_stick);
    const double slid = u0 * t + 0.5 * rate * t * t;
    expectClose("energy", r.energy(), e0 - s.mu_d * s.normal() * slid, energy_scale);
    if (HasFailure()) break;
  }
}

// ---- 7: topspin on a slope too steep to roll ----

TEST(RollerTransition, TopspinOnSteepSlopeTurnsIntoForwardSlip) {
  const Slope s{0.5, 0.4, 0.1, 0.05};  // tan 0.5 = 0.546 > 0.1 * 3.5
  const RollerParams p = makeParams(Shape::Sphere, s);
  ASSERT_FALSE(Roller::canRoll(p));
  const RollerInitial in{1.0, 1.0, 0.0, -40.0};
  const double u0 = in.v0 + in.omega0 * kRadius;
  const double t_zero = -u0 / s.slipRate(-1);
  assertNotOnStepBoundary(t_zero);
  Piecewise traj = startAt(in, s.slipAccel(-1), s.slipAlpha(-1));
  traj.then(t_zero, s.slipAccel(+1), s.slipAlpha(+1));
  ASSERT_GT(s.slipRate(+1), 0.0);

  Roller r(p, in);
  const RunLog log = runAndCompare(r, traj, 0, 10000);
  EXPECT_TRUE(log.stick_times.empty());
  for (const StepLog& st : log.steps) {
    ASSERT_EQ(st.mode, RollMode::Slipping) << "t = " << st.t;
    const double f = s.mu_d * s.normal();
    expectClose("force", st.friction, st.t < t_zero ? f : -f, f);
    // After the zero crossing u grows as slipRate(+1) (t - t_zero).
    if (st.t > t_zero) expectClose("u", st.u, s.slipRate(+1) * (st.t - t_zero), s.slipRate(+1) * 10.0);
  }
}

// ---- 8: uphill rolling launch ----

TEST(RollerRolling, UphillLaunchRollsUpStopsAndRollsBack) {
  const Slope s{0.349, 0.5, 0.3, 0.2};
  const RollerInitial in{5.0, -2.0, 0.0, 16.0};  // omega0 = -v0 / R exactly
  Roller r(makeParams(Shape::Cylinder, s), in);
  ASSERT_EQ(r.slipSpeed(), 0.0);
  ASSERT_EQ(r.mode(), RollMode::Rolling);
  const double t_turn = -in.v0 / s.rollAccel();
  assertNotOnStepBoundary(t_turn);
  const RunLog log = runAndCompare(r, startAt(in, s.rollAccel(), s.rollAlpha()), 0, 10000);
  EXPECT_EQ(log.restarts, 0);
  for (const StepLog& st : log.steps) ASSERT_EQ(st.mode, RollMode::Rolling) << "t = " << st.t;
  // The velocity changes sign between the two steps around t_turn = -v0 / A, and nowhere else.
  double v_prev = in.v0;
  Roller again(makeParams(Shape::Cylinder, s), in);
  for (int k = 1; k <= 10000; ++k) {
    again.step(kDt);
    const double v = again.state().v;
    const bool crossed = (v_prev < 0.0) != (v < 0.0);
    EXPECT_EQ(crossed, (k - 1) * kDt < t_turn && t_turn < k * kDt) << "k = " << k;
    v_prev = v;
  }
  // Highest point reached: x0 - v0^2 / (2 A), checked through the closed form at t_turn.
  const double x_top = in.x0 - in.v0 * in.v0 / (2.0 * s.rollAccel());
  expectClose("x", startAt(in, s.rollAccel(), s.rollAlpha()).at(t_turn).x, x_top, in.x0);
}

// ---- 9: hysteresis band ----

TEST(RollerHysteresis, RollingKeepsRollingAndForwardSlipNeverSticks) {
  // mu_d (1+c)/c = 0.35 < tan(phi) = 0.5 <= mu_s (1+c)/c = 0.7 for the sphere.
  const Slope s{std::atan(0.5), 0.4, 0.2, 0.1};
  ASSERT_GT(s.slipRate(+1), 0.0);
  const RollerParams p = makeParams(Shape::Sphere, s);
  ASSERT_TRUE(Roller::canRoll(p));

  const RollerInitial rest{0.0, 0.0, 0.0, 0.0};
  Roller rolling(p, rest);
  const RunLog roll_log = runAndCompare(rolling, startAt(rest, s.rollAccel(), s.rollAlpha()), 0, 10000);
  for (const StepLog& st : roll_log.steps) ASSERT_EQ(st.mode, RollMode::Rolling) << "t = " << st.t;

  const RollerInitial sliding{0.0, 1.0, 0.0, 0.0};
  Roller slipping(p, sliding);
  const RunLog slip_log =
      runAndCompare(slipping, startAt(sliding, s.slipAccel(+1), s.slipAlpha(+1)), 0, 10000);
  EXPECT_TRUE(slip_log.stick_times.empty());
  double u_prev = 1.0;
  for (const StepLog& st : slip_log.steps) {
    ASSERT_EQ(st.mode, RollMode::Slipping) << "t = " << st.t;
    ASSERT_GT(st.u, u_prev) << "t = " << st.t;
    u_prev = st.u;
  }
}

// ---- 10: setParams ----

TEST(RollerSetParams, LosingGripStartsForwardSlipAndRegainingItWaitsForZeroSlip) {
  const Slope grip{0.349, 0.4, 0.3, 0.2};
  const Slope slick{0.349, 0.4, 0.05, 0.04};  // tan 0.349 = 0.36 > 0.05 * 3.5
  const RollerParams grip_p = makeParams(Shape::Sphere, grip);
  const RollerParams slick_p = makeParams(Shape::Sphere, slick);
  ASSERT_FALSE(Roller::canRoll(slick_p));
  const RollerInitial rest{0.0, 0.0, 0.0, 0.0};
  Roller r(grip_p, rest);

  // 0..1 s rolling.
  Piecewise traj = startAt(rest, grip.rollAccel(), grip.rollAlpha());
  RunLog log = runAndCompare(r, traj, 0, 1000);
  EXPECT_EQ(log.started_slipping, 0);

  // 1..2 s slipping forward on the slick slope; the state is kept across setParams.
  const RollerMotion before = r.state();
  r.setParams(slick_p);
  EXPECT_EQ(r.state().x, before.x);
  EXPECT_EQ(r.state().v, before.v);
  EXPECT_EQ(r.state().theta, before.theta);
  EXPECT_EQ(r.state().omega, before.omega);
  traj.then(1.0, slick.slipAccel(+1), slick.slipAlpha(+1));
  log = runAndCompare(r, traj, 1000, 2000);
  ASSERT_FALSE(log.steps.empty());
  EXPECT_TRUE(log.steps.front().events.started_slipping);
  EXPECT_EQ(log.started_slipping, 1);
  EXPECT_TRUE(log.stick_times.empty());
  for (const StepLog& st : log.steps) {
    ASSERT_EQ(st.mode, RollMode::Slipping);
    expectClose("u", st.u, slick.slipRate(+1) * (st.t - 1.0), slick.slipRate(+1));
  }

  // From 2 s grip is back, but the body keeps slipping until u reaches 0.
  const double u2 = slick.slipRate(+1) * 1.0;
  const double t_stick = 2.0 - u2 / grip.slipRate(+1);
  assertNotOnStepBoundary(t_stick);
  r.setParams(grip_p);
  EXPECT_EQ(r.mode(), RollMode::Slipping);
  traj.then(2.0, grip.slipAccel(+1), grip.slipAlpha(+1));
  const double v_stick = traj.at(t_stick).v;
  traj.then(t_stick, grip.rollAccel(), grip.rollAlpha(), -v_stick / kRadius);
  log = runAndCompare(r, traj, 2000, 5000);
  EXPECT_EQ(log.started_slipping, 0);
  ASSERT_EQ(log.stick_times.size(), 1u);
  expectClose("t_stick", log.stick_times[0], t_stick, t_stick);
  for (const StepLog& st : log.steps) {
    ASSERT_EQ(st.mode, st.t < t_stick ? RollMode::Slipping : RollMode::Rolling) << "t = " << st.t;
  }
}

// ---- 11: ends of the slope ----

// Smallest step index whose closed-form x is off the slope, with a margin far above rounding.
int firstStepOff(const Piecewise& traj, double length) {
  for (int k = 1;; ++k) {
    const double x = traj.at(k * kDt).x;
    if (x > length || x < 0.0) {
      EXPECT_GT(std::min(std::abs(x - length), std::abs(x)), 1e-9);
      return k;
    }
  }
}

void checkRestarts(const Slope& s, const RollerInitial& in, double length) {
  const Piecewise traj = startAt(in, s.rollAccel(), s.rollAlpha());
  const int k_off = firstStepOff(traj, length);
  Roller r(makeParams(Shape::Sphere, s, length), in);
  ASSERT_EQ(r.mode(), RollMode::Rolling);
  for (int lap = 1; lap <= 2; ++lap) {
    for (int k = 1; k <= k_off; ++k) {
      const RollerStepEvents ev = r.step(kDt);
      ASSERT_EQ(ev.restarted, k == k_off) << "lap " << lap << " k = " << k;
    }
    EXPECT_EQ(r.laps(), lap);
    EXPECT_EQ(r.state().x, in.x0);
    EXPECT_EQ(r.state().v, in.v0);
    EXPECT_EQ(r.state().theta, in.theta0);
    EXPECT_EQ(r.state().omega, in.omega0);
    EXPECT_EQ(r.mode(), RollMode::Rolling);
  }
}

TEST(RollerSlopeEnds, RunningPastTheLowerEndRestarts) {
  checkRestarts(Slope{0.349, 0.4, 0.3, 0.2}, RollerInitial{0.5, 0.0, 0.1, 0.0}, 1.0);
}

TEST(RollerSlopeEnds, RunningPastTheUpperEndRestarts) {
  checkRestarts(Slope{0.349, 0.4, 0.3, 0.2}, RollerInitial{0.2, -2.0, 0.0, 16.0}, 1.0);
}

TEST(RollerSlopeEnds, RestartReDerivesTheSlippingMode) {
  // Launched sliding off a short slope: after the restart it slips again, as it did at the start.
  const Slope s{0.349, 0.4, 0.3, 0.2};
  const RollerInitial in{0.5, 3.0, 0.0, 0.0};
  Roller r(makeParams(Shape::Sphere, s, 1.0), in);
  bool restarted = false;
  for (int k = 0; k < 1000 && !restarted; ++k) restarted = r.step(kDt).restarted;
  ASSERT_TRUE(restarted);
  EXPECT_EQ(r.mode(), RollMode::Slipping);
  EXPECT_LT(r.frictionForce(), 0.0);
  EXPECT_EQ(r.state().v, in.v0);
}

TEST(RollerSlopeEnds, BothEndsThemselvesAreOnTheSlope) {
  // On a horizontal plane a body at rest stays exactly where it is.
  const Slope flat{0.0, 0.4, 0.3, 0.2};
  for (double x0 : {0.0, 1.0}) {
    Roller r(makeParams(Shape::Sphere, flat, 1.0), RollerInitial{x0, 0.0, 0.0, 0.0});
    for (int k = 0; k < 100; ++k) EXPECT_FALSE(r.step(kDt).restarted);
    EXPECT_EQ(r.state().x, x0);
    EXPECT_EQ(r.laps(), 0);
  }
}

// ---- 12: horizontal plane ----

TEST(RollerHorizontal, SlidingSphereSticksAtClosedFormTimeAndSpeed) {
  const Slope flat{0.0, 0.4, 0.3, 0.2};
  const double c = 0.4;
  const double v0 = 3.0;
  const RollerInitial in{1.0, v0, 0.0, 0.0};
  const double t_stick = v0 * c / (flat.mu_d * kG * (1.0 + c));
  const double v_final = v0 / (1.0 + c);
  assertNotOnStepBoundary(t_stick);
  Piecewise traj = startAt(in, -flat.mu_d * kG, -flat.mu_d * kG / (c * kRadius));
  traj.then(t_stick, 0.0, 0.0, -v_final / kRadius);

  Roller r(makeParams(Shape::Sphere, flat), in);
  const double inertia = c * kMass * kRadius * kRadius;
  const double l0 = -kMass * kRadius * v0;  // L_z about the contact point: I omega - M R v
  const RunLog log = runAndCompare(r, traj, 0, 3000);
  ASSERT_EQ(log.stick_times.size(), 1u);
  expectClose("t_stick", log.stick_times[0], t_stick, t_stick);
  expectClose("v", r.state().v, v_final, v_final);
  // Friction acts at the contact point and gravity balances the normal force, so L_z is conserved.
  Roller again(makeParams(Shape::Sphere, flat), in);
  for (int k = 1; k <= 3000; ++k) {
    again.step(kDt);
    const double l = inertia * again.state().omega - kMass * kRadius * again.state().v;
    expectClose("L_contact", l, l0, std::abs(l0));
  }
}

// ---- 13: reset, setInitial, mirror symmetry ----

// The roller's state is exactly these initial conditions.
void expectAt(const Roller& r, const RollerInitial& initial) {
  EXPECT_EQ(r.state().x, initial.x0);
  EXPECT_EQ(r.state().v, initial.v0);
  EXPECT_EQ(r.state().theta, initial.theta0);
  EXPECT_EQ(r.state().omega, initial.omega0);
}

TEST(RollerReset, ResetAndSetInitialRestoreStateAndMode) {
  const Slope s{0.349, 0.4, 0.3, 0.2};
  const RollerInitial sliding{0.5, 3.0, 0.2, 0.0};
  Roller r(makeParams(Shape::Sphere, s, 2.0), sliding);
  for (int k = 0; k < 3000; ++k) r.step(kDt);  // sticks, and runs off the end at least once
  ASSERT_GE(r.laps(), 1);
  r.reset();
  expectAt(r, sliding);
  EXPECT_EQ(r.mode(), RollMode::Slipping);
  EXPECT_LT(r.frictionForce(), 0.0);
  EXPECT_EQ(r.laps(), 0);

  const RollerInitial topspin{0.7, 1.0, 0.0, -40.0};
  r.setInitial(topspin);
  EXPECT_EQ(r.initial().x0, topspin.x0);
  EXPECT_EQ(r.initial().omega0, topspin.omega0);
  expectAt(r, topspin);
  EXPECT_EQ(r.mode(), RollMode::Slipping);
  EXPECT_GT(r.frictionForce(), 0.0);

  const RollerInitial rolling{0.3, 0.5, 0.0, -4.0};  // u0 = 0.5 - 4 * 0.125 = 0
  r.setInitial(rolling);
  EXPECT_EQ(r.mode(), RollMode::Rolling);
  expectClose("force", r.frictionForce(), s.rollFriction(), std::abs(s.rollFriction()));
}

// A progress kept while slipping and put back after the body has stuck, rolled and restarted: the mode,
// the laps and the motion are back, and the steps from there are those of a body that never left.
TEST(RollerReset, RestoredProgressRepeatsTheSameStepsBitForBit) {
  const Slope s{0.349, 0.4, 0.3, 0.2};
  Roller r(makeParams(Shape::Sphere, s, 2.0), RollerInitial{0.5, 3.0, 0.2, 0.0});
  for (int k = 0; k < 50; ++k) r.step(kDt);
  ASSERT_EQ(r.mode(), RollMode::Slipping);
  const Roller::Progress kept = r.progress();
  const Roller reference = r;
  for (int k = 0; k < 3000; ++k) r.step(kDt);  // sticks, and runs off the end at least once
  ASSERT_GE(r.laps(), 1);
  r.restore(kept);
  EXPECT_EQ(r.mode(), RollMode::Slipping);
  EXPECT_EQ(r.laps(), 0);
  Roller never_left = reference;
  for (int k = 0; k < 3000; ++k) {
    const RollerStepEvents a = r.step(kDt);
    const RollerStepEvents b = never_left.step(kDt);
    ASSERT_EQ(a.stuck_at, b.stuck_at) << "step " << k;
    ASSERT_EQ(a.restarted, b.restarted) << "step " << k;
    ASSERT_EQ(r.state().x, never_left.state().x) << "step " << k;
    ASSERT_EQ(r.state().v, never_left.state().v) << "step " << k;
    ASSERT_EQ(r.state().theta, never_left.state().theta) << "step " << k;
    ASSERT_EQ(r.state().omega, never_left.state().omega) << "step " << k;
    ASSERT_EQ(r.mode(), never_left.mode()) << "step " << k;
    ASSERT_EQ(r.laps(), never_left.laps()) << "step " << k;
  }
}

TEST(RollerReset, MirroredLaunchOnHorizontalPlaneGivesMirroredTrajectory) {
  const Slope flat{0.0, 0.4, 0.3, 0.2};
  const double x0 = 100.0;
  Roller a(makeParams(Shape::Sphere, flat), RollerInitial{x0, 3.0, 0.5, 10.0});
  Roller b(makeParams(Shape::Sphere, flat), RollerInitial{x0, -3.0, -0.5, -10.0});
  double sx = 0.0, sv = 3.0, sth = 0.5, sw = 10.0;  // largest magnitudes so far
  int sticks = 0;
  for (int k = 1; k <= 5000; ++k) {
    const RollerStepEvents ea = a.step(kDt);
    const RollerStepEvents eb = b.step(kDt);
    ASSERT_EQ(ea.stuck_at.has_value(), eb.stuck_at.has_value()) << "k = " << k;
    if (ea.stuck_at) {
      ++sticks;
      expectClose("t_stick", *eb.stuck_at, *ea.stuck_at, kDt);
    }
    const RollerMotion& p = a.state();
    const RollerMotion& q = b.state();
    sx = std::max(sx, std::abs(p.x - x0));
    sv = std::max(sv, std::abs(p.v));
    sth = std::max(sth, std::abs(p.theta));
    sw = std::max(sw, std::abs(p.omega));
    expectClose("mirror", q.x - x0, -(p.x - x0), std::max(sx, 1e-3));
    expectClose("mirror", q.v, -p.v, sv);
    expectClose("mirror", q.theta, -p.theta, sth);
    expectClose("mirror", q.omega, -p.omega, sw);
    ASSERT_EQ(a.mode(), b.mode());
  }
  EXPECT_EQ(sticks, 1);
}

// ---- 14: frictionless slipping ----

TEST(RollerFrictionless, SlippingBodyNeverSticksAndKeepsItsSpin) {
  const Slope s{0.349, 0.4, 0.3, 0.0};
  const RollerInitial in{0.0, 1.0, 0.0, 5.0};
  Roller r(makeParams(Shape::Sphere, s), in);
  const RunLog log = runAndCompare(r, startAt(in, kG * std::sin(s.phi), 0.0), 0, 10000);
  EXPECT_TRUE(log.stick_times.empty());
  for (const StepLog& st : log.steps) {
    ASSERT_EQ(st.mode, RollMode::Slipping);
    ASSERT_EQ(st.friction, 0.0);
  }
  EXPECT_EQ(r.state().omega, in.omega0);
}

TEST(RollerFrictionless, SlidingOnHorizontalPlaneKeepsEverythingConstant) {
  const Slope flat{0.0, 0.4, 0.3, 0.0};
  const RollerInitial in{0.0, 2.0, 0.0, 0.0};
  Roller r(makeParams(Shape::Sphere, flat), in);
  const RunLog log = runAndCompare(r, startAt(in, 0.0, 0.0), 0, 10000);
  EXPECT_TRUE(log.stick_times.empty());
  for (const StepLog& st : log.steps) ASSERT_EQ(st.mode, RollMode::Slipping);
  EXPECT_EQ(r.state().v, in.v0);
  EXPECT_EQ(r.state().omega, in.omega0);
}

}  // namespace
}  // namespace rigid_body_sim
