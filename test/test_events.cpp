// The core's events (core/event.h) against the truth: each instant against the closed forms of section
// 16.3.2 (closedFormRun) for random launches of every incline type, the state they carry against the model
// at that instant, a rod's contacts against its ends' heights step by step, the race's places, the restarts
// a change makes; and every event of a generated run of every type names a kind its type declares.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "rigid_body_sim/core/state_fields.h"
#include "rigid_body_sim/core/world.h"
#include "rigid_body_sim/run/session.h"

using namespace rigid_body_sim;

namespace {

constexpr double kTimeTolerance = 1e-9;  // s: the rounding of a few closed-form steps (as test_race)

WorldConfig worldOf(std::vector<BodyConfig> bodies, bool race = false) {
  WorldConfig config;
  config.race = race;
  config.bodies = std::move(bodies);
  return config;
}

// Every event until `until` s.
std::vector<BodyEvent> eventsOf(World& world, double until) {
  std::vector<BodyEvent> events;
  while (world.time() < until) {
    world.step();
    for (auto& event : world.takeEvents()) events.push_back(std::move(event));
  }
  return events;
}

const BodyEvent* firstOf(const std::vector<BodyEvent>& events, const std::string& kind) {
  for (const auto& event : events) {
    if (event.kind == kind) return &event;
  }
  return nullptr;
}

double number(const std::vector<EventValue>& values, const std::string& name) {
  const EventValue* value = findValue(values, name);
  return value ? value->number : std::nan("");
}

RollerConfig randomRoller(std::mt19937_64& random, int draw) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  RollerConfig config;
  config.params.shape = namedShapes()[static_cast<std::size_t>(draw) % 4];
  config.params.inertia_factor = inertiaFactorOf(config.params.shape);
  config.params.incline_angle = 0.05 + 1.2 * unit(random);
  config.params.mu_s = 0.05 + 0.5 * unit(random);
  config.params.mu_d = config.params.mu_s * unit(random);
  config.initial.x0 = 2.5;
  config.initial.v0 = -2.0 + 8.0 * unit(random);
  config.initial.omega0 = -60.0 + 120.0 * unit(random);
  return config;
}

BlockConfig randomBlock(std::mt19937_64& random) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  BlockConfig config;
  config.params.incline_angle = 0.02 + 0.9 * unit(random);
  config.params.mu_s = 0.05 + 0.8 * unit(random);
  config.params.mu_d = config.params.mu_s * unit(random);
  config.initial.x0 = 2.5;
  config.initial.v0 = -6.0 + 12.0 * unit(random);
  return config;
}

}  // namespace

// Random launches of every shape: the first slip_to_roll and finished of a lap at the closed form's instants,
// the finish's lap_time and closed_form values equal to them, its speed the state's v; at slip_to_roll the
// body rolls (omega = -v / R exactly, as the model lands it) in the state the event carries.
TEST(Events, RollerInstantsAreTheClosedForms) {
  std::mt19937_64 random(5201);
  int rolled = 0;
  int finished = 0;
  for (int draw = 0; draw < 200; ++draw) {
    const RollerConfig config = randomRoller(random, draw);
    SCOPED_TRACE("draw " + std::to_string(draw) + ": c " + std::to_string(config.params.inertia_factor) +
                 ", phi " + std::to_string(config.params.incline_angle) + ", mu " +
                 std::to_string(config.params.mu_s) + "/" + std::to_string(config.params.mu_d) + ", v0 " +
                 std::to_string(config.initial.v0) + ", omega0 " + std::to_string(config.initial.omega0));
    const RollerRun expected = closedFormRun(config.params, config.initial);
    World world(worldOf({{"ball", config}}));
    std::vector<BodyEvent> events;
    while (world.time() < 30.0 && !firstOf(events, "finished")) {
      world.step();
      for (auto& event : world.takeEvents()) events.push_back(std::move(event));
    }
    const BodyEvent* roll = firstOf(events, "slip_to_roll");
    const BodyEvent* finish = firstOf(events, "finished");
    ASSERT_EQ(roll != nullptr,
              expected.slip_to_roll && (!expected.finish || *expected.slip_to_roll < *expected.finish))
        << "closed form: rolls at " << expected.slip_to_roll.value_or(-1) << ", finishes at "
        << expected.finish.value_or(-1) << "; stepped: " << (roll ? roll->t : -1) << ", "
        << (finish ? finish->t : -1);
    ASSERT_EQ(finish != nullptr, expected.finish.has_value());
    if (roll) {
      ++rolled;
      SCOPED_TRACE("rolled at " + std::to_string(roll->t) +
                   (finish ? ", finished at " + std::to_string(finish->t) : ""));
      EXPECT_NEAR(roll->t, *expected.slip_to_roll, kTimeTolerance);
      EXPECT_EQ(findValue(roll->state, "mode")->text, "rolling");
      EXPECT_EQ(number(roll->state, "omega"), -number(roll->state, "v") / config.params.radius);  // u = 0
    }
    if (finish) {
      ++finished;
      EXPECT_NEAR(finish->t, *expected.finish, kTimeTolerance);
      EXPECT_EQ(number(finish->values, "lap_time"), finish->t);  // its first lap started at t = 0
      EXPECT_EQ(number(finish->values, "closed_form"), *expected.finish);
      EXPECT_EQ(number(finish->values, "speed"), number(finish->state, "v"));
      const double x = number(finish->state, "x");
      EXPECT_TRUE(x == 0.0 || x == config.params.incline_length) << "on an end of its slope: " << x;
      EXPECT_TRUE(std::isnan(number(finish->values, "place"))) << "a place only in a race";
    }
  }
  EXPECT_GT(rolled, 20);  // both kinds are covered
  EXPECT_GT(finished, 150);
}

// Random launches of a block: came_to_rest at the closed form's stop, at rest in the state it carries, and
// finished at the closed form's finish.
TEST(Events, BlockInstantsAreTheClosedForms) {
  std::mt19937_64 random(5202);
  int stopped = 0;
  int finished = 0;
  for (int draw = 0; draw < 200; ++draw) {
    const BlockConfig config = randomBlock(random);
    SCOPED_TRACE("draw " + std::to_string(draw));
    const BlockRun expected = closedFormRun(config.params, config.initial);
    World world(worldOf({{"block", config}}));
    std::vector<BodyEvent> events;
    while (world.time() < 30.0 && !firstOf(events, "finished")) {
      world.step();
      for (auto& event : world.takeEvents()) events.push_back(std::move(event));
    }
    const BodyEvent* rest = firstOf(events, "came_to_rest");
    const BodyEvent* finish = firstOf(events, "finished");
    const bool sticks = std::tan(config.params.incline_angle) <= config.params.mu_s;
    ASSERT_EQ(rest != nullptr, expected.stops && sticks && !expected.finish);
    ASSERT_EQ(finish != nullptr, expected.finish.has_value());
    if (rest) {
      ++stopped;
      EXPECT_NEAR(rest->t, *expected.stops, kTimeTolerance);
      EXPECT_EQ(number(rest->state, "v"), 0.0);
      EXPECT_EQ(findValue(rest->state, "mode")->text, "sticking");
    }
    if (finish) {
      ++finished;
      EXPECT_NEAR(finish->t, *expected.finish, kTimeTolerance);
      EXPECT_EQ(number(finish->values, "closed_form"), *expected.finish);
    }
  }
  EXPECT_GT(stopped, 20);
  EXPECT_GT(finished, 20);
}

// A rod's contact_began and contact_ended come in the step at whose end an end is first below the floor or
// first above it again (its height, as the force model computes it), with that end's name; every bounce of
// random drops for 5 s.
TEST(Events, RodContactsAreTheStepsAnEndCrossesTheFloor) {
  std::mt19937_64 random(5203);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int contacts = 0;
  for (int draw = 0; draw < 10; ++draw) {
    RodConfig config;
    config.initial.theta = 2.0 * M_PI * unit(random);
    config.initial.y = 1.0 + 3.0 * unit(random);
    World world(worldOf({{"rod", config}}));
    Rod twin(config.params, config.initial);
    unsigned below = 0;
    while (world.time() < 5.0) {
      world.step();
      twin.step(world.dt());
      const unsigned now = (twin.endHeightA() < 0.0 ? 1u : 0u) | (twin.endHeightB() < 0.0 ? 2u : 0u);
      std::set<std::string> expected;
      for (const unsigned end : {1u, 2u}) {
        if ((now & end) != (below & end)) {
          expected.insert(std::string((now & end) ? "contact_began " : "contact_ended ") +
                          (end == 1u ? "A" : "B"));
        }
      }
      std::set<std::string> got;
      for (const auto& event : world.takeEvents()) {
        got.insert(event.kind + " " + findValue(event.values, "end")->text);
        EXPECT_EQ(event.t, world.time());
        EXPECT_EQ(number(event.state, "y"), twin.state().y);
      }
      ASSERT_EQ(got, expected) << "draw " << draw << " at t = " << world.time();
      contacts += static_cast<int>(got.size());
      below = now;
    }
  }
  EXPECT_GT(contacts, 40);
}

// In a race each finish carries its place, from the times (ties share one), and the lap's restart comes
// with cause "race" for every racer together.
TEST(Events, RaceFinishesCarryPlacesAndTheNextLapRestartsAll) {
  RollerConfig sphere;
  RollerConfig twin = sphere;  // a tie
  RollerConfig ring;
  ring.params.shape = Shape::Ring;
  ring.params.inertia_factor = 1.0;
  World world(worldOf({{"sphere", sphere}, {"twin", twin}, {"ring", ring}}, true));
  std::vector<BodyEvent> events = eventsOf(world, 8.0);
  std::map<std::string, double> places;
  std::map<std::string, int> restarts;
  for (const auto& event : events) {
    if (event.kind == "finished" && !places.count(event.body))
      places[event.body] = number(event.values, "place");
    if (event.kind == "lap_restarted") {
      EXPECT_EQ(findValue(event.values, "cause")->text, "race");
      ++restarts[event.body];
    }
  }
  EXPECT_EQ(places, (std::map<std::string, double>{{"sphere", 1}, {"twin", 1}, {"ring", 3}}));
  EXPECT_EQ(restarts, (std::map<std::string, int>{{"sphere", 1}, {"twin", 1}, {"ring", 1}}));
}

// A reset restarts every body with cause "reset"; a reconfigure of an initial condition restarts that body
// ("reconfigure"); a spawned body starts with "spawn"; each at the instant of the change, with the state it
// restarts in. A set_state in mid-lap leaves the lap's finish without its closed form.
TEST(Events, ChangesRestartBodiesWithTheirCause) {
  RollerConfig sphere;
  RodConfig rod;
  World world(worldOf({{"rod", rod}, {"sphere", sphere}}));
  eventsOf(world, 0.5);
  WorldCommand reset;
  reset.kind = WorldCommand::Kind::Reset;
  reset.step = world.stepCount();
  world.apply(reset);
  const std::vector<BodyEvent> after_reset = world.takeEvents();
  ASSERT_EQ(after_reset.size(), 2u);
  for (const auto& event : after_reset) {
    EXPECT_EQ(event.t, world.time());
    EXPECT_EQ(findValue(event.values, "cause")->text, "reset");
    EXPECT_EQ(event.kind, event.body == "rod" ? "restarted" : "lap_restarted");
  }
  EXPECT_EQ(number(after_reset[1].state, "x"), sphere.initial.x0);

  WorldCommand spawn;
  spawn.kind = WorldCommand::Kind::Spawn;
  spawn.step = world.stepCount();
  spawn.body = spawn.config.name = "block";
  spawn.config.config = BlockConfig{};
  world.apply(spawn);
  const std::vector<BodyEvent> spawned = world.takeEvents();
  ASSERT_EQ(spawned.size(), 1u);
  EXPECT_EQ(spawned[0].body, "block");
  EXPECT_EQ(findValue(spawned[0].values, "cause")->text, "spawn");

  WorldCommand moved;
  moved.kind = WorldCommand::Kind::SetState;
  moved.step = world.stepCount();
  moved.body = "sphere";
  moved.state = {{"x", 1.0}};
  world.apply(moved);
  const std::vector<BodyEvent> rest = eventsOf(world, 4.0);
  const BodyEvent* finish = nullptr;
  for (const auto& event : rest) {
    if (event.body == "sphere" && event.kind == "finished") finish = finish ? finish : &event;
  }
  ASSERT_NE(finish, nullptr);
  EXPECT_EQ(findValue(finish->values, "closed_form"), nullptr) << "moved in mid-lap: no closed form holds";
}

// Over a generated run of every type (launches, changes of friction that make rolling bodies slip), every
// event names a kind of its body's type, in time order, its state the type's fields; and every kind but
// those only a change makes happens.
TEST(Events, EveryEventIsAKindOfItsType) {
  std::map<std::string, std::set<std::string>> declared;
  for (const auto& [type, kinds] : eventKindsByType()) {
    for (const auto& kind : kinds) declared[type].insert(kind.name);
  }
  std::mt19937_64 random(5204);
  std::vector<BodyConfig> bodies;
  for (int i = 0; i < 8; ++i) {
    bodies.push_back({"roller" + std::to_string(i), randomRoller(random, i)});
    bodies.push_back({"block" + std::to_string(i), randomBlock(random)});
  }
  RodConfig rod;
  rod.params.floor_length = 6.0;  // it runs off: a restart
  bodies.push_back({"rod", rod});
  RollerConfig rolling;  // from rest on 20 degrees, still rolling down its long slope when the change comes
  rolling.params.incline_length = 100.0;
  bodies.push_back({"rolling", rolling});
  BlockConfig resting;  // at rest where static friction holds it
  resting.params.mu_s = 0.5;
  bodies.push_back({"resting", resting});
  Session session(worldOf(bodies), {}, 10);
  std::map<std::string, std::set<std::string>> seen;
  double last = 0.0;
  for (int second = 0; second < 6; ++second) {
    session.advance(1000);
    if (second == 2) {  // too steep for static friction: rolling rollers slip, resting blocks slide
      for (const auto& body : session.world().bodies()) {
        WorldCommand command;
        command.kind = WorldCommand::Kind::Reconfigure;
        command.body = body.name;
        command.config = session.world().config().bodies[*session.world().indexOf(body.name)];
        std::visit(
            [](auto& config) {
              if constexpr (!std::is_same_v<std::decay_t<decltype(config)>, RodConfig>) {
                config.params.incline_angle = 1.2;
                config.params.mu_s = 0.1;
                config.params.mu_d = 0.05;
              }
            },
            command.config.config);
        session.apply(command);
      }
    }
    for (const auto& event : session.takeEvents()) {
      EXPECT_GE(event.t, last);
      last = event.t;
      ASSERT_TRUE(declared[event.type].count(event.kind)) << event.type << " " << event.kind;
      const Body* body = nullptr;
      for (const auto& b : session.world().bodies()) body = b.name == event.body ? &b : body;
      ASSERT_NE(body, nullptr);
      ASSERT_EQ(event.type, typeName(*body));
      std::vector<std::string> fields;
      for (const auto& field : event.state) fields.push_back(field.name);
      EXPECT_EQ(fields, stateFieldNames(*body));
      seen[event.type].insert(event.kind);
    }
  }
  EXPECT_EQ(seen, declared) << "a kind the run did not show";
}
