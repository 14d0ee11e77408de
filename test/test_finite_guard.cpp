// The node's NaN guard (run/finite_guard): which quantity is non-finite, holding a body at its last
// finite state while the others go on exactly as without it, reporting each fault once, releasing.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "rigid_body_sim/core/world.h"
#include "rigid_body_sim/run/finite_guard.h"
#include "test_util.h"

namespace rigid_body_sim {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

WorldConfig rodAndSphere() {
  WorldConfig config;
  config.bodies.push_back({"rod", RodConfig{}});
  config.bodies.push_back({"sphere", RollerConfig{}});
  return config;
}

// A rod whose moment of inertia M L^2 / 12 underflows to 0 although every value is in its range:
// its angular acceleration is 0 / 0 from the first step (the one path to NaN through valid input found).
RodConfig degenerateRod() {
  RodConfig rod;
  rod.params.mass = 1e-200;
  rod.params.length = 1e-100;
  rod.params.k = 1e-200;  // keeps sqrt(4 k / M) ordinary, so no sub-stepping
  return rod;
}

// The core state of a body's messages, for exact comparison.
std::vector<double> stateOf(const Body& body) {
  if (const auto* rod = std::get_if<Rod>(&body.model)) {
    const RodMotion& s = rod->state();
    return {s.x, s.y, s.theta, s.vx, s.vy, s.omega};
  }
  const RollerMotion& s = std::get<Roller>(body.model).state();
  return {s.x, s.v, s.theta, s.omega};
}

TEST(NonFiniteField, NamesTheFirstNonFiniteQuantityOfARod) {
  World world(rodAndSphere());
  Rod& rod = std::get<Rod>(world.bodies()[0].model);
  EXPECT_FALSE(nonFiniteField(world.bodies()[0]));
  EXPECT_TRUE(finiteState(world.bodies()[0]));
  for (const auto& [field, motion] : std::vector<std::pair<std::string, RodMotion>>{
           {"x", {kNaN, 4, 0.3, 2, 0, 0}},
           {"y", {0, kInf, 0.3, 2, 0, 0}},
           {"theta", {0, 4, -kInf, 2, 0, 0}},
           {"vx", {0, 4, 0.3, kNaN, 0, 0}},
           {"vy", {0, 4, 0.3, 2, kNaN, 0}},
           {"omega", {0, 4, 0.3, 2, 0, kInf}},
           {"energy", {0, 4, 0.3, 2, 1e300, 0}}}) {  // every field finite, v^2 overflows
    rod.setInitial(motion);
    ASSERT_TRUE(nonFiniteField(world.bodies()[0])) << field;
    EXPECT_EQ(field, *nonFiniteField(world.bodies()[0]));
    EXPECT_FALSE(finiteState(world.bodies()[0]));
  }
}

TEST(NonFiniteField, NamesTheFirstNonFiniteQuantityOfARoller) {
  World world(rodAndSphere());
  Roller& sphere = std::get<Roller>(world.bodies()[1].model);
  EXPECT_FALSE(nonFiniteField(world.bodies()[1]));
  sphere.setInitial({0, kNaN, 0, 0});
  EXPECT_EQ("v", nonFiniteField(world.bodies()[1]).value_or("none"));
  sphere.setInitial({0, 0, 0, -kInf});
  EXPECT_EQ("omega", nonFiniteField(world.bodies()[1]).value_or("none"));
  RollerParams params = sphere.params();
  params.mu_d = kNaN;  // a kinetic friction that no validation would let through
  sphere.setParams(params);
  sphere.setInitial({0, 1, 0, 0});  // slipping: the friction force uses mu_d
  EXPECT_EQ("friction", nonFiniteField(world.bodies()[1]).value_or("none"));
}

// The guard's cheap check: a motion within kSurelyFiniteMotion at the corner of every validated range (the
// largest parameters, the motion at the bound with either sign) still gives finite messages; beyond the
// bound the full check decides.
TEST(SurelyFinite, HoldsAtTheCornerOfTheValidatedRanges) {
  const double b = kSurelyFiniteMotion;
  WorldConfig config;
  RodConfig rod;
  rod.params.mass = 1e9;
  rod.params.length = 1e6;
  rod.params.k = 1e12;
  rod.params.gravity = 1e3;
  config.bodies.push_back({"rod", rod});
  RollerConfig roller;
  roller.params.shape = Shape::Custom;
  roller.params.inertia_factor = 100;
  roller.params.mass = 1e9;
  roller.params.radius = 1e6;
  roller.params.gravity = 1e3;
  roller.params.incline_angle = 1.5;
  roller.params.mu_s = roller.params.mu_d = 100;
  config.bodies.push_back({"roller", roller});
  World world(config);
  for (const double sign : {1.0, -1.0}) {
    std::get<Rod>(world.bodies()[0].model).setInitial({b, sign * b, b, sign * b, b, sign * b});
    std::get<Roller>(world.bodies()[1].model).setInitial({b, sign * b, b, sign * b});  // slipping
    for (const Body& body : world.bodies()) {
      EXPECT_TRUE(surelyFinite(body)) << body.name;
      EXPECT_FALSE(nonFiniteField(body)) << body.name << ": " << nonFiniteField(body).value_or("");
    }
  }
  std::get<Rod>(world.bodies()[0].model).setInitial({0, 4, 0.3, 1e200, 0, 0});  // v^2 overflows
  EXPECT_FALSE(surelyFinite(world.bodies()[0]));
  EXPECT_EQ("energy", nonFiniteField(world.bodies()[0]).value_or("none"));
  std::get<Rod>(world.bodies()[0].model).setInitial({0, 4, kNaN, 2, 0, 0});
  EXPECT_FALSE(surelyFinite(world.bodies()[0]));
}

TEST(DescribeBody, ListsEveryKeyAndTheState) {
  World world(rodAndSphere());
  const std::string rod = describeBody(world.bodies()[0]);
  for (const char* part :
       {"length=1 ", "mass=0.5 ", "k=1000 ", "y0=4 ", "theta0=0.3 ", "integrator=euler_cromer", "gravity=9.8",
        "| state x=0 y=4 theta=0.3 vx=2 vy=0 omega=0 energy="}) {
    EXPECT_NE(std::string::npos, rod.find(part)) << part << " in " << rod;
  }
  const std::string sphere = describeBody(world.bodies()[1]);
  for (const char* part :
       {"radius=0.1 ", "mu_s=0.3 ", "mu_d=0.2 ", "shape=sphere", "mode=rolling", "friction="}) {
    EXPECT_NE(std::string::npos, sphere.find(part)) << part << " in " << sphere;
  }
  // Every key its type writes, as a config file writes it.
  const auto expectEveryKey = [](const std::string& text, const auto& config) {
    for (const auto& key : bodyType<std::decay_t<decltype(config)>>().keys) {
      if (key.written())
        EXPECT_NE(text.find(std::string(key.name) + "=" + key.text(config) + " "), std::string::npos)
            << key.name << " in " << text;
    }
  };
  expectEveryKey(rod, std::get<RodConfig>(world.config().bodies[0].config));
  expectEveryKey(sphere, std::get<RollerConfig>(world.config().bodies[1].config));
}

// A fault injected into the rod after 100 steps: the rod is held at its state of step 100, the sphere
// runs on exactly as in a world without any guard, and the fault is reported once.
TEST(FiniteGuard, HoldsTheFaultyBodyAndLetsTheOthersGoOn) {
  World world(rodAndSphere());
  World reference(rodAndSphere());
  FiniteGuard guard(world.bodies());
  for (int i = 0; i < 100; ++i) {
    world.step();
    reference.step();
    EXPECT_TRUE(guard.afterStep(world.bodies()).empty());
  }
  const std::vector<double> held_at = stateOf(world.bodies()[0]);
  world.step();
  reference.step();
  std::get<Rod>(world.bodies()[0].model).setInitial({0, 4, kNaN, 2, 0, 0});  // what a bad step would leave
  const auto faults = guard.afterStep(world.bodies());
  ASSERT_EQ(1u, faults.size());
  EXPECT_EQ(0u, faults[0].index);
  EXPECT_EQ("theta", faults[0].field);
  EXPECT_TRUE(guard.held(0));
  EXPECT_FALSE(guard.held(1));
  EXPECT_EQ(held_at, stateOf(world.bodies()[0]));
  for (int i = 0; i < 500; ++i) {
    world.step();
    reference.step();
    EXPECT_TRUE(guard.afterStep(world.bodies()).empty()) << "reported again at step " << i;
    ASSERT_EQ(held_at, stateOf(world.bodies()[0]));
    ASSERT_EQ(stateOf(reference.bodies()[1]), stateOf(world.bodies()[1]));
  }
}

TEST(FiniteGuard, ReleasedBodyRunsAgain) {
  World world(rodAndSphere());
  FiniteGuard guard(world.bodies());
  std::get<Rod>(world.bodies()[0].model).setInitial({kNaN, 4, 0.3, 2, 0, 0});
  ASSERT_EQ(1u, guard.afterStep(world.bodies()).size());
  world.reset();  // back to the initial conditions, which are the NaN ones here
  std::get<Rod>(world.bodies()[0].model).setInitial({0, 4, 0.3, 2, 0, 0});
  guard.releaseAll(world.bodies());
  EXPECT_FALSE(guard.held(0));
  world.step();
  EXPECT_TRUE(guard.afterStep(world.bodies()).empty());
  EXPECT_GT(std::get<Rod>(world.bodies()[0].model).state().x, 0.0);  // it moved
}

TEST(FiniteGuard, ReleasingANonFiniteBodyHoldsItAgainWithoutLosingItsLastFiniteState) {
  World world(rodAndSphere());
  FiniteGuard guard(world.bodies());
  const std::vector<double> initial = stateOf(world.bodies()[0]);
  std::get<Rod>(world.bodies()[0].model).setInitial({0, kNaN, 0.3, 2, 0, 0});
  ASSERT_EQ(1u, guard.afterStep(world.bodies()).size());
  std::get<Rod>(world.bodies()[0].model).setInitial({0, kNaN, 0.3, 2, 0, 0});
  guard.release(0, world.bodies()[0]);
  const auto again = guard.afterStep(world.bodies());
  ASSERT_EQ(1u, again.size());  // a new fault after a release is a new report
  EXPECT_EQ(initial, stateOf(world.bodies()[0]));
}

// The one path to a non-finite state through values within their ranges that was known, a rod whose moment
// of inertia M L^2 / 12 underflows to 0 (0 / 0 at its first step), is refused before it runs: validation
// checks what is derived from the keys too. The guard stays, for a path nobody knows yet; the tests above
// put non-finite values into a body directly.
TEST(FiniteGuard, TheDegenerateRodIsRefusedBeforeItRuns) {
  WorldConfig config;
  config.bodies.push_back({"tiny", degenerateRod()});
  const std::string refusal = test::refusalOf([&] { validate(config); });
  EXPECT_NE(refusal.find("body 'tiny', key 'mass, length': value moment of inertia M L^2 / 12 = 0"),
            std::string::npos)
      << refusal;
}

}  // namespace
}  // namespace rigid_body_sim
