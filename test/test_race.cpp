// A race (WorldConfig::race): the rollers start together, each stops at the end of its slope with its time,
// and all start a new lap together once every one has finished; each finish time and slip-to-roll instant
// against the closed forms of section 16.3.2 (closedFormRun), for random shapes, slopes, friction and
// launches (sliding, backspin, topspin, uphill).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <random>
#include <string>

#include "rigid_body_sim/core/world.h"
#include "rigid_body_sim/io/config_loader.h"
#include "test_util.h"

using namespace rigid_body_sim;

namespace {

RollerConfig roller(Shape shape, double angle, double mu_s, double mu_d, double v0 = 0.0,
                    double omega0 = 0.0) {
  RollerConfig config;
  config.params.shape = shape;
  config.params.inertia_factor = inertiaFactorOf(shape);
  config.params.incline_angle = angle;
  config.params.mu_s = mu_s;
  config.params.mu_d = mu_d;
  config.initial.v0 = v0;
  config.initial.omega0 = omega0;
  return config;
}

WorldConfig race(std::vector<BodyConfig> bodies) {
  WorldConfig config;
  config.race = true;
  config.bodies = std::move(bodies);
  return config;
}

// The book's race below the critical angles: sphere, cylinder and ring from rest on 20 degrees.
WorldConfig threeShapes() {
  return race({{"sphere", roller(Shape::Sphere, 0.349, 0.2, 0.15)},
               {"cylinder", roller(Shape::Cylinder, 0.349, 0.2, 0.15)},
               {"ring", roller(Shape::Ring, 0.349, 0.2, 0.15)}});
}

constexpr double kTimeTolerance = 1e-9;  // s: rounding of a few closed-form steps, far below a step

}  // namespace

// Rolling from rest: x = a t^2 / 2 with a = g sin(phi) / (1 + c), so the time down L is sqrt(2 L / a).
TEST(ClosedFormRun, RollingFromRestTakesSqrtTwoLOverA) {
  const RollerConfig sphere = roller(Shape::Sphere, 0.349, 0.3, 0.2);
  const double a = kDefaultGravity * std::sin(0.349) / 1.4;
  const RollerRun run = closedFormRun(sphere.params, sphere.initial);
  ASSERT_TRUE(run.finish);
  EXPECT_NEAR(*run.finish, std::sqrt(2 * 5.0 / a), 1e-12);
  EXPECT_FALSE(run.slip_to_roll);
}

// A ball launched sliding without spin: u = v, du/dt = g sin(phi) - mu_d g cos(phi) (1 + c) / c, so it rolls
// from t = -v0 / (du/dt) (section 16.3.2's "various initial conditions").
TEST(ClosedFormRun, ALaunchedBallRollsFromMinusUOverDuDt) {
  const RollerConfig ball = roller(Shape::Sphere, 0.05, 0.3, 0.2, 4.0);
  const double dudt = kDefaultGravity * (std::sin(0.05) - 0.2 * std::cos(0.05) * 3.5);
  const RollerRun run = closedFormRun(ball.params, ball.initial);
  ASSERT_TRUE(run.slip_to_roll);
  EXPECT_NEAR(*run.slip_to_roll, -4.0 / dudt, 1e-12);
}

// The three shapes released together: each holds at the bottom with its time, in the order of a = g sin /
// (1 + c) (sphere, cylinder, ring); the results stand World::kRaceResultsShown after the ring finishes, then
// all start again together from the top.
TEST(Race, ShapesWaitAtTheBottomThenStartTogether) {
  World world(threeShapes());
  std::vector<std::string> order;
  while (order.size() < 3) {
    world.step();
    for (const auto& event : world.takeEvents()) {
      if (event.kind == "finished") order.push_back(event.body);
    }
    ASSERT_LT(world.time(), 10.0) << "not all finished";
    for (const auto& body : world.bodies()) {
      const auto& model = std::get<Roller>(body.model);
      if (body.finish) {
        EXPECT_TRUE(model.finished());
        EXPECT_EQ(model.state().x, model.params().incline_length) << body.name << " held at the bottom";
      }
    }
  }
  EXPECT_EQ(order, (std::vector<std::string>{"sphere", "cylinder", "ring"}));
  const std::int64_t last_finished = world.stepCount();
  while (world.bodies()[0].finish) world.step();
  EXPECT_EQ(world.stepCount() - last_finished,
            static_cast<std::int64_t>(World::kRaceResultsShown * world.rate()));
  // The next lap: every body at the top, no result.
  for (const auto& body : world.bodies()) {
    const auto& model = std::get<Roller>(body.model);
    EXPECT_FALSE(body.finish) << body.name;
    EXPECT_FALSE(model.finished()) << body.name;
    EXPECT_EQ(model.state().x, 0.0) << body.name;
    EXPECT_EQ(model.state().v, 0.0) << body.name;
    EXPECT_EQ(model.laps(), 1) << body.name;
  }
}

// Places in the order of the times, each time the closed form's, in the first lap and the next ones.
TEST(Race, TimesAreTheClosedFormsLapAfterLap) {
  World world(threeShapes());
  int laps = 0;
  std::vector<RaceFinish> results(3);
  while (laps < 3) {
    world.step();
    for (std::size_t i = 0; i < 3; ++i) {
      if (world.bodies()[i].finish) results[i] = *world.bodies()[i].finish;
    }
    for (const auto& event : world.takeEvents()) {
      if (event.kind != "lap_restarted" || event.body != "ring") continue;
      ++laps;
      for (std::size_t i = 0; i < 3; ++i) {
        SCOPED_TRACE(world.bodies()[i].name + " lap " + std::to_string(laps));
        ASSERT_TRUE(results[i].closed_form);
        EXPECT_NEAR(results[i].time, *results[i].closed_form, kTimeTolerance);
        EXPECT_EQ(results[i].place, static_cast<int>(i) + 1);
      }
    }
  }
}

// Random launches: every finish (and slip-to-roll instant) of the stepped run within 1e-9 s of the closed
// form, whatever the shape, slope, friction, speed and spin.
TEST(Race, RandomLaunchesFinishAtTheClosedFormTimes) {
  std::mt19937_64 random(16032);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const std::array<Shape, 4> shapes = namedShapes();
  int finished = 0;
  int stuck = 0;
  for (int draw = 0; draw < 200; ++draw) {
    const double mu_s = 0.05 + 0.5 * unit(random);
    RollerConfig config = roller(shapes[draw % 4], 0.05 + 1.2 * unit(random), mu_s, mu_s * unit(random),
                                 -2.0 + 8.0 * unit(random), -60.0 + 120.0 * unit(random));
    config.initial.x0 = 2.5;
    SCOPED_TRACE("draw " + std::to_string(draw) + ": " + toString(config.params.shape) + " on " +
                 std::to_string(config.params.incline_angle) + " rad, v0 " +
                 std::to_string(config.initial.v0) + ", omega0 " + std::to_string(config.initial.omega0));
    const RollerRun expected = closedFormRun(config.params, config.initial);
    World world(race({{"ball", config}}));
    std::optional<double> rolled;
    while (world.time() < 30.0 && world.bodies()[0].finish == std::nullopt) {
      world.step();
      for (const auto& event : world.takeEvents()) {
        if (event.kind == "slip_to_roll" && !rolled) rolled = event.t;
      }
      if (world.bodies()[0].finish) break;
    }
    const auto& finish = world.bodies()[0].finish;
    ASSERT_EQ(finish.has_value(), expected.finish.has_value());
    if (finish) {
      EXPECT_NEAR(finish->time, *expected.finish, kTimeTolerance);
      EXPECT_EQ(finish->closed_form, expected.finish);
    }
    ASSERT_EQ(rolled.has_value(), expected.slip_to_roll.has_value());
    if (rolled) EXPECT_NEAR(*rolled, *expected.slip_to_roll, kTimeTolerance);
    finished += finish ? 1 : 0;
    stuck += rolled ? 1 : 0;
  }
  // The draws cover both events (a draw with neither would check nothing).
  EXPECT_GT(finished, 150);  // 200 and 40 with this seed
  EXPECT_GT(stuck, 20);
}

// Outside a race a roller restarts alone at the bottom, exactly as before (no hold, no result).
TEST(Race, WithoutARaceEachRestartsAlone) {
  WorldConfig config = threeShapes();
  config.race = false;
  World world(config);
  for (int step = 0; step < 3000; ++step) world.step();  // 3 s: the sphere (2.0 s) is on its second lap
  const auto& sphere = std::get<Roller>(world.bodies()[0].model);
  EXPECT_EQ(sphere.laps(), 1);
  EXPECT_FALSE(sphere.finished());
  EXPECT_FALSE(world.bodies()[0].finish);
}

// A reset starts a new lap for all; a racer whose initial conditions change restarts the race.
TEST(Race, ResetAndANewStartRestartTheRace) {
  World world(threeShapes());
  for (int step = 0; step < 2100; ++step) world.step();  // the sphere is down, the others not
  ASSERT_TRUE(world.bodies()[0].finish);
  world.reset();
  for (const auto& body : world.bodies()) {
    EXPECT_FALSE(body.finish);
    EXPECT_EQ(std::get<Roller>(body.model).state().x, 0.0);
  }
  for (int step = 0; step < 2100; ++step) world.step();
  ASSERT_TRUE(world.bodies()[0].finish);
  EXPECT_NEAR(world.bodies()[0].finish->time, *world.bodies()[0].finish->closed_form, kTimeTolerance);
  WorldCommand command;
  command.kind = WorldCommand::Kind::Reconfigure;
  command.step = world.stepCount();
  command.body = "ring";
  command.config = world.config().bodies[2];
  std::get<RollerConfig>(command.config.config).initial.v0 = 0.5;
  world.apply(command);
  for (const auto& body : world.bodies()) {
    EXPECT_FALSE(body.finish) << body.name;
    EXPECT_EQ(std::get<Roller>(body.model).state().x, 0.0) << body.name;
  }
}

// The lesson's slip part (config/race_slip.yaml): three shapes bowled with backspin slip, then roll at
// t = (v0 + omega0 R) / (g mu_d cos(phi) (1 + 1/c) - g sin(phi)), the times its comment gives (0.77, 0.92,
// 1.54 s), in every lap; each lap's finish at the closed form's.
TEST(Race, TheSlipLessonRollsAtTheSlipPhaseClosedForm) {
  World world(loadWorldConfigFile(test::config("race_slip.yaml")));
  const std::map<std::string, double> stated{{"sphere", 0.77}, {"cylinder", 0.92}, {"ring", 1.54}};
  std::map<std::string, double> rolls_at;
  for (const auto& body : world.bodies()) {
    const Roller& model = std::get<Roller>(body.model);
    const RollerParams& p = model.params();
    const RollerMotion& start = model.state();
    const double g = world.config().gravity;
    const double slip = start.v + start.omega * p.radius;  // u = v + omega R, 0 while rolling
    const double slip_rate =
        g * std::sin(p.incline_angle) - g * p.mu_d * std::cos(p.incline_angle) * (1 + 1 / p.inertia_factor);
    ASSERT_GT(slip, 0.0) << body.name << " launched sliding";
    rolls_at[body.name] = -slip / slip_rate;
    EXPECT_NEAR(rolls_at[body.name], stated.at(body.name), 0.005) << body.name << ": the config's comment";
  }
  std::map<std::string, int> rolled;
  std::map<std::string, double> lap_start{{"sphere", 0.0}, {"cylinder", 0.0}, {"ring", 0.0}};
  const auto lapsRolled = [&] {
    int fewest = 3;
    for (const auto& [name, at] : rolls_at) fewest = std::min(fewest, rolled[name]);
    return fewest;
  };
  while (lapsRolled() < 3 && world.time() < 20.0) {  // laps of about 4.4 s
    world.step();
    for (const auto& event : world.takeEvents()) {
      SCOPED_TRACE(event.body + " at t = " + std::to_string(event.t));
      const Body& body = world.bodies()[event.body == "sphere" ? 0 : event.body == "cylinder" ? 1 : 2];
      ASSERT_EQ(body.name, event.body);
      if (event.kind == "lap_restarted") lap_start[event.body] = event.t;
      if (event.kind == "slip_to_roll") {
        EXPECT_NEAR(event.t - lap_start[event.body], rolls_at.at(event.body), kTimeTolerance);
        ++rolled[event.body];
      }
      if (event.kind == "roll_to_slip") ADD_FAILURE() << "slips again after rolling";
      if (event.kind == "finished") EXPECT_NEAR(body.finish->time, *body.finish->closed_form, kTimeTolerance);
    }
  }
  EXPECT_EQ(lapsRolled(), 3);
}
