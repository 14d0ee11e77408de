// The node's NaN guard (run/finite_guard): which quantity is non-finite, holding a body at its last
// finite state while the others go on exactly as without it, reporting each fault once, releasing.
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "rigid_body_sim/core/body_types.h"
#include "rigid_body_sim/core/state_fields.h"
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
  FiniteGuard guard(world.bodies(), world.dt());
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

// The guard as World::step's own observer: the world names it a body that its step left non-finite (here
// an energy beyond a double), which it holds at its state of the step before, while the other runs on.
TEST(FiniteGuard, TheWorldNamesItABodyItsStepLeftNonFinite) {
  World world(rodAndSphere());
  World reference(rodAndSphere());
  FiniteGuard guard(world.bodies(), world.dt());
  for (int i = 0; i < 70; ++i) {
    world.step(&guard);
    reference.step();
  }
  ASSERT_TRUE(guard.takeNewlyHeld().empty());
  const std::vector<double> held_at = stateOf(reference.bodies()[0]);
  std::get<Rod>(world.bodies()[0].model).setInitial({0, 4, 0.3, 1e200, 0, 0});  // what a bad step would leave
  world.step(&guard);
  reference.step();
  const auto faults = guard.takeNewlyHeld();
  ASSERT_EQ(1u, faults.size());
  EXPECT_EQ("energy", faults[0].field);
  EXPECT_TRUE(guard.held(0));
  EXPECT_EQ(held_at, stateOf(world.bodies()[0]));
  EXPECT_EQ(stateOf(reference.bodies()[1]), stateOf(world.bodies()[1]));
}

// The guard as World::step's observer, with a fault in body 0 right after its step to `fault_step` (its x
// NaN, as a step gone wrong would leave it: test/faults/fault_injection.h does the same in the node).
class FaultyStep : public BodyStepObserver {
 public:
  FaultyStep(const World& world, std::int64_t fault_step)
      : guard(world.bodies(), world.dt()), world_(world), fault_step_(fault_step) {}
  void afterUnsureStep(std::size_t index, Body& body) override { guard.afterUnsureStep(index, body); }
  void afterBodiesStep(std::vector<Body>& bodies) override {
    if (world_.stepCount() + 1 == fault_step_) {
      std::visit(
          [](auto& model) {
            auto state = model.state();
            state.x = kNaN;
            model.setState(state);
          },
          bodies[0].model);
      guard.afterUnsureStep(0, bodies[0]);
    }
    guard.afterBodiesStep(bodies);
  }
  void movedByWorld(std::size_t index, Body& body) override { guard.movedByWorld(index, body); }

  FiniteGuard guard;

 private:
  const World& world_;
  std::int64_t fault_step_;
};

// Every state field of a body, numbers and texts, for exact comparison whatever its type.
std::vector<std::string> fieldsOf(const Body& body) {
  std::vector<std::string> out;
  std::visit(
      [&](const auto& model) {
        for (const auto& field : stateFields(model)) {
          std::ostringstream text;
          text << field.name << '=' << std::hexfloat << field.number << field.text;  // every bit
          out.push_back(text.str());
        }
      },
      body.model);
  return out;
}

// The guard keeps a body's progress every kStepsPerKeep steps only and steps it again to the last finite
// state at a fault: for every body type and faults at and around the keeping points, the body is held at
// its state of the step before the fault, that of a world without a guard, bit for bit, and stays there.
TEST(FiniteGuard, HoldsEveryTypeAtItsStateOfTheStepBeforeTheFault) {
  const std::int64_t keep = FiniteGuard::kStepsPerKeep;
  for (const std::int64_t fault :
       {std::int64_t{1}, std::int64_t{2}, keep - 1, keep, keep + 1, 3 * keep + 17, 40 * keep + 5}) {
    BodyTypes::forEach([&](auto type) {
      using Type = decltype(type);
      WorldConfig config;
      typename Type::Config body{};
      if constexpr (std::is_same_v<Type, RollerType>) body.initial.v0 = 3.0;  // slipping first
      config.bodies = {{"body", body}, {"other", RodConfig{}}};
      World world(config);
      World reference(config);
      FaultyStep observer(world, fault);
      for (std::int64_t i = 0; i + 1 < fault; ++i) {
        world.step(&observer);
        reference.step();
      }
      ASSERT_TRUE(observer.guard.takeNewlyHeld().empty()) << Type::kName;
      const auto held_at = fieldsOf(reference.bodies()[0]);
      for (int i = 0; i < 3; ++i) {
        world.step(&observer);
        reference.step();
        ASSERT_EQ(held_at, fieldsOf(world.bodies()[0])) << Type::kName << ", fault at step " << fault;
        ASSERT_EQ(fieldsOf(reference.bodies()[1]), fieldsOf(world.bodies()[1])) << Type::kName;
      }
      const auto faults = observer.guard.takeNewlyHeld();
      ASSERT_EQ(1u, faults.size()) << Type::kName;
      EXPECT_EQ("x", faults[0].field);
    });
  }
}

// A race's next lap moves the racers in World::step, after their steps were observed: a fault just after
// it holds a racer at its state in the new lap, not at one stepped on from the lap before.
TEST(FiniteGuard, HoldsARacerAtItsStateInTheLapAfterARestart) {
  WorldConfig config;
  config.race = true;
  RollerConfig racer;
  racer.params.incline_length = 0.3;
  config.bodies = {{"sphere", racer}};
  racer.params.shape = Shape::Ring;
  racer.params.inertia_factor = inertiaFactorOf(Shape::Ring);
  config.bodies.push_back({"ring", racer});
  World probe(config);
  std::int64_t restart = 0;  // the step whose end restarted the race
  while (restart == 0 && probe.time() < 20.0) {
    probe.step();
    for (const auto& event : probe.takeEvents()) {
      const EventValue* cause = findValue(event.values, "cause");
      if (cause && cause->text == "race") restart = probe.stepCount();
    }
  }
  ASSERT_GT(restart, 0) << "no race restart within 20 s";
  for (const std::int64_t after : {1, 2, 30}) {
    World world(config);
    World reference(config);
    FaultyStep observer(world, restart + after);
    while (world.stepCount() + 1 < restart + after) {
      world.step(&observer);
      reference.step();
    }
    world.step(&observer);
    ASSERT_EQ(1u, observer.guard.takeNewlyHeld().size());
    EXPECT_EQ(fieldsOf(reference.bodies()[0]), fieldsOf(world.bodies()[0])) << after << " steps after";
  }
}

TEST(FiniteGuard, ReleasedBodyRunsAgain) {
  World world(rodAndSphere());
  FiniteGuard guard(world.bodies(), world.dt());
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
  FiniteGuard guard(world.bodies(), world.dt());
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
