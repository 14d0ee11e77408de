// World::apply: a change made while the world runs equals a world built with it, and a refused one changes
// nothing (the world then runs on exactly like one that never saw it).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "rigid_body_sim/core/state_fields.h"
#include "rigid_body_sim/core/world.h"
#include "test_util.h"

using namespace rigid_body_sim;
using rigid_body_sim::test::rodAndBall;

namespace {

BodyConfig ring(const std::string& name) {
  RollerConfig ring;
  ring.params.shape = Shape::Ring;
  ring.params.inertia_factor = 1.0;
  ring.params.incline_angle = 0.4;
  ring.initial.x0 = 0.5;
  return {name, ring};
}

WorldCommand command(WorldCommand::Kind kind, const World& world, const std::string& body = "") {
  WorldCommand made;
  made.kind = kind;
  made.step = world.stepCount();
  made.body = body;
  return made;
}

void steps(World& world, int count) {
  for (int i = 0; i < count; ++i) world.step();
}

// Every reported field bit for bit (a roller's mode as its text).
void expectSameState(const Body& a, const Body& b) {
  ASSERT_EQ(a.name, b.name);
  ASSERT_EQ(typeName(a), typeName(b));
  const auto compare = [&](const auto& x, const auto& y) {
    for (std::size_t i = 0; i < x.size(); ++i) {
      EXPECT_EQ(std::memcmp(&x[i].number, &y[i].number, sizeof(double)), 0)
          << a.name << " " << x[i].name << ": " << x[i].number << " vs " << y[i].number;
      EXPECT_EQ(x[i].text, y[i].text) << a.name << " " << x[i].name;
    }
  };
  std::visit(
      [&](const auto& x) {
        compare(stateFields(x), stateFields(std::get<std::decay_t<decltype(x)>>(b.model)));
      },
      a.model);
}

void expectSameWorld(const World& a, const World& b) {
  ASSERT_EQ(a.stepCount(), b.stepCount());
  ASSERT_EQ(a.bodies().size(), b.bodies().size());
  ASSERT_EQ(a.config().bodies.size(), a.bodies().size());
  for (std::size_t i = 0; i < a.bodies().size(); ++i) {
    expectSameState(a.bodies()[i], b.bodies()[i]);
    EXPECT_EQ(a.config().bodies[i].name, a.bodies()[i].name);
  }
}

}  // namespace

TEST(Commands, SpawnedBodyEqualsAWorldBuiltWithItAtThatStep) {
  World world(rodAndBall());
  steps(world, 137);
  WorldCommand spawn = command(WorldCommand::Kind::Spawn, world, "hoop");
  spawn.config = ring("hoop");
  world.apply(spawn);
  ASSERT_EQ(world.bodies().size(), 3u);
  EXPECT_EQ(world.config().bodies.back().name, "hoop");
  steps(world, 500);

  World before(rodAndBall());  // the bodies that were there run on untouched
  steps(before, 637);
  WorldConfig alone;
  alone.bodies.push_back(ring("hoop"));
  World hoop(alone);  // the spawned one as if it had started at t = 0
  steps(hoop, 500);
  expectSameState(world.bodies()[0], before.bodies()[0]);
  expectSameState(world.bodies()[1], before.bodies()[1]);
  expectSameState(world.bodies()[2], hoop.bodies()[0]);
}

TEST(Commands, SpawnTakesTheWorldsGravity) {
  WorldConfig config = rodAndBall();
  config.gravity = 1.62;
  World world(config);
  WorldCommand spawn = command(WorldCommand::Kind::Spawn, world, "hoop");
  spawn.config = ring("hoop");
  world.apply(spawn);
  EXPECT_EQ(std::get<Roller>(world.bodies()[2].model).params().gravity, 1.62);
  EXPECT_EQ(std::get<RollerConfig>(world.config().bodies[2].config).params.gravity, 1.62);
}

TEST(Commands, DeleteLeavesTheOthersAsTheyWere) {
  World world(rodAndBall());
  steps(world, 250);
  world.apply(command(WorldCommand::Kind::Delete, world, "rod"));
  steps(world, 250);
  ASSERT_EQ(world.bodies().size(), 1u);
  ASSERT_EQ(world.config().bodies.size(), 1u);
  World reference(rodAndBall());
  steps(reference, 500);
  expectSameState(world.bodies()[0], reference.bodies()[1]);
  // The last body stays: a world of none is no config.
  EXPECT_THROW(world.apply(command(WorldCommand::Kind::Delete, world, "ball")), ConfigError);
}

TEST(Commands, SetStateMovesTheBodyNowAndKeepsItsInitialConditions) {
  World world(rodAndBall());
  steps(world, 100);
  WorldCommand set = command(WorldCommand::Kind::SetState, world, "rod");
  set.state = {{"x", 1.5}, {"vy", -2.0}, {"omega", 3.0}};
  RodMotion expected = std::get<Rod>(world.bodies()[0].model).state();
  expected.x = 1.5;
  expected.vy = -2.0;
  expected.omega = 3.0;
  world.apply(set);
  steps(world, 300);

  Rod reference(RodParams{}, expected);
  for (int i = 0; i < 300; ++i) reference.step(world.dt());
  const Rod& rod = std::get<Rod>(world.bodies()[0].model);
  EXPECT_EQ(std::memcmp(&rod.state(), &reference.state(), sizeof(RodMotion)), 0);
  EXPECT_EQ(rod.initial().x, RodMotion{}.x);
  world.apply(command(WorldCommand::Kind::Reset, world));
  EXPECT_EQ(std::memcmp(&rod.state(), &rod.initial(), sizeof(RodMotion)), 0);
}

TEST(Commands, SetStateGivesARollerTheModeOfItsNewSpeeds) {
  World world(rodAndBall());
  steps(world, 10);
  const double radius = std::get<Roller>(world.bodies()[1].model).params().radius;
  WorldCommand set = command(WorldCommand::Kind::SetState, world, "ball");
  set.state = {{"v", 2.0}, {"omega", -2.0 / radius}};
  world.apply(set);
  EXPECT_EQ(std::get<Roller>(world.bodies()[1].model).mode(), RollMode::Rolling);
  set = command(WorldCommand::Kind::SetState, world, "ball");
  set.state = {{"omega", 0.0}};
  world.apply(set);
  EXPECT_EQ(std::get<Roller>(world.bodies()[1].model).mode(), RollMode::Slipping);
  EXPECT_EQ(std::get<Roller>(world.bodies()[1].model).initial().v0, 3.0);
}

TEST(Commands, SetStateRefusesAnyOtherFieldAndChangesNothing) {
  World world(rodAndBall());
  steps(world, 10);
  const RodMotion before = std::get<Rod>(world.bodies()[0].model).state();
  const std::string rod_fields = "x, y, theta, vx, vy, omega)";
  const std::pair<std::vector<StateValue>, std::string> refused[] = {
      {{{"vz", 1.0}},
       "body 'rod', key 'vz': value 1 is not allowed (allowed: no such state field of a rod; "},
      {{{"x", 1.0}, {"v", 2.0}},
       "body 'rod', key 'v': value 2 is not allowed (allowed: no such state field of "},
      {{{"energy", 3.0}},
       "body 'rod', key 'energy': value 3 is not allowed (allowed: no such state field of "},
  };
  for (const auto& [state, message] : refused) {
    WorldCommand set = command(WorldCommand::Kind::SetState, world, "rod");
    set.state = state;
    try {
      world.apply(set);
      ADD_FAILURE() << state.back().field << " was accepted";
    } catch (const ConfigError& error) {
      const std::string what = error.what();
      EXPECT_EQ(what.substr(0, message.size()), message);
      EXPECT_EQ(what.substr(what.size() - rod_fields.size()), rod_fields) << what;
    }
    EXPECT_EQ(std::memcmp(&std::get<Rod>(world.bodies()[0].model).state(), &before, sizeof(RodMotion)), 0);
  }
  WorldCommand set = command(WorldCommand::Kind::SetState, world, "ball");
  set.state = {{"y", 1.0}};
  EXPECT_THROW(
      {
        try {
          world.apply(set);
        } catch (const ConfigError& error) {
          EXPECT_EQ(
              std::string(error.what()),
              "body 'ball', key 'y': value 1 is not allowed (allowed: no such state field of a roller; its "
              "fields: x, v, theta, omega)");
          throw;
        }
      },
      ConfigError);
}

// A set field takes the range of its initial condition: the key whose state field it is.
TEST(Commands, EverySettableFieldHasAnInitialCondition) {
  for (const auto& name : stateFieldNames<RodType>(true)) {
    EXPECT_NE(keyOfStateField<RodConfig>(name), nullptr) << name;
  }
  for (const auto& name : stateFieldNames<RollerType>(true)) {
    EXPECT_NE(keyOfStateField<RollerConfig>(name), nullptr) << name;
  }
}

// The fields' names and numbers, in order.
template <class Fields>
void expectFields(const Fields& fields, const std::vector<std::pair<std::string, double>>& expected) {
  ASSERT_EQ(fields.size(), expected.size());
  for (std::size_t i = 0; i < fields.size(); ++i) {
    EXPECT_EQ(fields[i].name, expected[i].first);
    EXPECT_EQ(fields[i].number, expected[i].second) << fields[i].name;
  }
}

// The tables read each field from the body's own member.
TEST(StateFields, AreTheBodysOwnValues) {
  const Rod rod(RodParams{}, RodMotion{1.0, 2.0, 3.0, 4.0, 5.0, 6.0});
  const RodMotion& r = rod.state();
  expectFields(stateFields(rod), {{"x", r.x},
                                  {"y", r.y},
                                  {"theta", r.theta},
                                  {"vx", r.vx},
                                  {"vy", r.vy},
                                  {"omega", r.omega},
                                  {"energy", rod.energy()}});
  EXPECT_EQ(r.vy, 5.0);

  const Roller ball(RollerParams{}, RollerInitial{1.0, 2.0, 3.0, 4.0});
  const RollerMotion& b = ball.state();
  expectFields(stateFields(ball), {{"x", b.x},
                                   {"v", b.v},
                                   {"theta", b.theta},
                                   {"omega", b.omega},
                                   {"mode", 0.0},
                                   {"friction", ball.frictionForce()},
                                   {"normal", ball.normalForce()},
                                   {"energy", ball.energy()}});
  EXPECT_EQ(stateFields(ball)[4].text, "slipping");  // u = v + omega R = 2.4 > 0
  EXPECT_EQ(b.v, 2.0);
}

TEST(Commands, ResetIsTheWorldsReset) {
  World world(rodAndBall());
  World reference(rodAndBall());
  steps(world, 321);
  steps(reference, 321);
  world.apply(command(WorldCommand::Kind::Reset, world));
  reference.reset();
  steps(world, 100);
  steps(reference, 100);
  expectSameWorld(world, reference);
}

TEST(Commands, ReconfigureRestartsOnlyWhenTheInitialConditionsChange) {
  World world(rodAndBall());
  steps(world, 200);
  const RodMotion before = std::get<Rod>(world.bodies()[0].model).state();
  WorldCommand reconfigure = command(WorldCommand::Kind::Reconfigure, world, "rod");
  reconfigure.config = world.config().bodies[0];
  std::get<RodConfig>(reconfigure.config.config).params.k = 2000.0;
  world.apply(reconfigure);
  const Rod& rod = std::get<Rod>(world.bodies()[0].model);
  EXPECT_EQ(std::memcmp(&rod.state(), &before, sizeof(RodMotion)), 0);
  EXPECT_EQ(rod.params().k, 2000.0);
  EXPECT_EQ(std::get<RodConfig>(world.config().bodies[0].config).params.k, 2000.0);

  std::get<RodConfig>(reconfigure.config.config).initial.y = 2.5;
  world.apply(reconfigure);
  EXPECT_EQ(rod.state().y, 2.5);
  EXPECT_EQ(rod.initial().y, 2.5);
}

TEST(Commands, ConfigReplacesEveryBodyAndTimeGoesOn) {
  World world(rodAndBall());
  steps(world, 50);
  WorldCommand config = command(WorldCommand::Kind::Config, world);
  config.world = rodAndBall();
  config.world.bodies.pop_back();
  world.apply(config);
  EXPECT_EQ(world.stepCount(), 50);
  ASSERT_EQ(world.bodies().size(), 1u);
  EXPECT_EQ(std::get<Rod>(world.bodies()[0].model).state().y, RodMotion{}.y);
}

TEST(Commands, AtMostMaxBodies) {
  WorldConfig config;
  config.bodies.push_back({"rod", RodConfig{}});
  World world(config);
  for (std::size_t i = 1; i < kMaxBodies; ++i) {
    WorldCommand spawn = command(WorldCommand::Kind::Spawn, world, "r" + std::to_string(i));
    spawn.config = {spawn.body, RodConfig{}};
    world.apply(spawn);
  }
  ASSERT_EQ(world.bodies().size(), kMaxBodies);
  WorldCommand spawn = command(WorldCommand::Kind::Spawn, world, "one_more");
  spawn.config = {spawn.body, RodConfig{}};
  try {
    world.apply(spawn);
    FAIL() << "spawned past the maximum";
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("at most 1000 bodies"), std::string::npos) << error.what();
  }
  EXPECT_EQ(world.bodies().size(), kMaxBodies);
}

// Each refused with one line; the world then runs on exactly like one that never saw it.
TEST(Commands, RefusedCommandsChangeNothing) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  World world(rodAndBall(), {"markers", "spawn"});
  World reference(rodAndBall(), {"markers", "spawn"});
  steps(world, 77);
  steps(reference, 77);

  std::vector<WorldCommand> refused;
  const auto add = [&](WorldCommand::Kind kind, const std::string& body, auto&& edit) {
    WorldCommand made = command(kind, world, body);
    edit(made);
    refused.push_back(made);
  };
  const auto none = [](WorldCommand&) {};
  const auto rodNamed = [](const std::string& name) {
    return [name](WorldCommand& c) { c.config = {name, RodConfig{}}; };
  };
  add(WorldCommand::Kind::Spawn, "rod", rodNamed("rod"));              // duplicate
  add(WorldCommand::Kind::Spawn, "markers", rodNamed("markers"));      // reserved by the node
  add(WorldCommand::Kind::Spawn, "rate", rodNamed("rate"));            // a world key
  add(WorldCommand::Kind::Spawn, "9lives", rodNamed("9lives"));        // invalid name
  add(WorldCommand::Kind::Spawn, "", rodNamed(""));                    // empty name
  add(WorldCommand::Kind::Spawn, "rod_floor", rodNamed("rod_floor"));  // its frame is the rod's fixed frame
  add(WorldCommand::Kind::Spawn, "world", rodNamed("world"));          // the world frame
  add(WorldCommand::Kind::Spawn, "a", rodNamed("b"));                  // a name that is not the body's
  add(WorldCommand::Kind::Spawn, "heavy", [](WorldCommand& c) {
    RodConfig rod;
    rod.params.mass = -1.0;
    c.config = {"heavy", rod};
  });
  add(WorldCommand::Kind::Spawn, "nan", [&](WorldCommand& c) {
    RodConfig rod;
    rod.initial.y = nan;
    c.config = {"nan", rod};
  });
  add(WorldCommand::Kind::Spawn, "offslope", [](WorldCommand& c) {
    BodyConfig body = ring("offslope");
    std::get<RollerConfig>(body.config).initial.x0 = 9.0;
    c.config = body;
  });
  add(WorldCommand::Kind::Delete, "nobody", none);
  add(WorldCommand::Kind::Delete, "", none);
  add(WorldCommand::Kind::Reconfigure, "nobody", rodNamed("nobody"));
  add(WorldCommand::Kind::Reconfigure, "rod", [](WorldCommand& c) { c.config = ring("rod"); });  // a new type
  add(WorldCommand::Kind::Reconfigure, "ball", [&](WorldCommand& c) {
    c.config = world.config().bodies[1];
    std::get<RollerConfig>(c.config.config).params.mu_d = 0.9;  // above mu_s
  });
  add(WorldCommand::Kind::SetState, "rod", none);                                              // no field
  add(WorldCommand::Kind::SetState, "rod", [](WorldCommand& c) { c.state = {{"v", 1.0}}; });   // a roller's
  add(WorldCommand::Kind::SetState, "ball", [](WorldCommand& c) { c.state = {{"y", 1.0}}; });  // a rod's
  add(WorldCommand::Kind::SetState, "rod", [](WorldCommand& c) { c.state = {{"energy", 1.0}}; });  // derived
  add(WorldCommand::Kind::SetState, "rod", [&](WorldCommand& c) { c.state = {{"x", 1.0}, {"y", nan}}; });
  add(WorldCommand::Kind::SetState, "rod", [](WorldCommand& c) { c.state = {{"vx", 1e9}}; });  // out of range
  add(WorldCommand::Kind::SetState, "rod", [](WorldCommand& c) { c.state = {{"x", 1.0}, {"x", 2.0}}; });
  // off the slope
  add(WorldCommand::Kind::SetState, "ball", [](WorldCommand& c) { c.state = {{"x", 2e6}}; });
  add(WorldCommand::Kind::SetState, "ball", [](WorldCommand& c) { c.state = {{"x", -0.1}}; });
  add(WorldCommand::Kind::SetState, "nobody", [](WorldCommand& c) { c.state = {{"x", 1.0}}; });
  WorldCommand late = command(WorldCommand::Kind::Reset, world);
  late.step = world.stepCount() + 1;  // not the world's step
  refused.push_back(late);

  for (const WorldCommand& bad : refused) {
    try {
      world.apply(bad);
      ADD_FAILURE() << "accepted " << toString(bad.kind) << " of '" << bad.body << "'";
    } catch (const ConfigError& error) {
      EXPECT_EQ(std::string(error.what()).find('\n'), std::string::npos);
    }
  }
  expectSameWorld(world, reference);
  steps(world, 300);
  steps(reference, 300);
  expectSameWorld(world, reference);
}

TEST(Commands, KindsHaveTheirNames) {
  for (const auto kind :
       {WorldCommand::Kind::Config, WorldCommand::Kind::Reconfigure, WorldCommand::Kind::Spawn,
        WorldCommand::Kind::Delete, WorldCommand::Kind::SetState, WorldCommand::Kind::Reset}) {
    EXPECT_EQ(commandKindFromString(toString(kind)), kind);
  }
  EXPECT_FALSE(commandKindFromString("teleport"));
  EXPECT_EQ(stateFieldNames<RodType>(true),
            (std::vector<std::string>{"x", "y", "theta", "vx", "vy", "omega"}));
  EXPECT_EQ(stateFieldNames<RollerType>(true), (std::vector<std::string>{"x", "v", "theta", "omega"}));
}
