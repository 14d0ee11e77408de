// The world: one clock kept as a step count, bodies stepped exactly as on their own, events in time.
#include <gtest/gtest.h>

#include <cmath>

#include "rigid_body_sim/core/world.h"
#include "test_util.h"

using namespace rigid_body_sim;
using rigid_body_sim::test::rodAndBall;

TEST(World, TimeIsAStepCountWithoutAccumulatedRounding) {
  WorldConfig config = rodAndBall();
  config.rate = 1000.0;
  World world(config);
  for (int i = 0; i < 100000; ++i) world.step();
  EXPECT_EQ(world.stepCount(), 100000);
  EXPECT_EQ(world.time(), 100.0);  // a sum of 100000 dt = 0.001 would be off in the last digits
  EXPECT_EQ(world.dt(), 0.001);
}

TEST(World, StepsEveryBodyAsOnItsOwn) {
  const WorldConfig config = rodAndBall();
  World world(config);
  Rod rod(std::get<RodConfig>(config.bodies[0].config).params,
          std::get<RodConfig>(config.bodies[0].config).initial);
  const auto& ball_config = std::get<RollerConfig>(config.bodies[1].config);
  Roller ball(ball_config.params, ball_config.initial);
  for (int i = 0; i < 3000; ++i) {
    world.step();
    rod.step(world.dt());
    ball.step(world.dt());
  }
  const Rod& world_rod = std::get<Rod>(world.find("rod")->model);
  const Roller& world_ball = std::get<Roller>(world.find("ball")->model);
  EXPECT_EQ(world_rod.state().x, rod.state().x);
  EXPECT_EQ(world_rod.state().y, rod.state().y);
  EXPECT_EQ(world_rod.state().theta, rod.state().theta);
  EXPECT_EQ(world_ball.state().x, ball.state().x);
  EXPECT_EQ(world_ball.state().omega, ball.state().omega);
  EXPECT_EQ(world.find("nobody"), nullptr);
}

TEST(World, ReportsTheSlipToRollInstantInsideTheStep) {
  const WorldConfig config = rodAndBall();
  const RollerParams& p = std::get<RollerConfig>(config.bodies[1].config).params;
  const double c = p.inertia_factor;
  const double du_dt =
      p.gravity * (std::sin(p.incline_angle) - p.mu_d * std::cos(p.incline_angle) * (1 + c) / c);
  const double expected = -3.0 / du_dt;  // u0 = v0 = 3 m/s, omega0 = 0
  World world(config);
  std::vector<BodyEvent> events;
  while (world.time() < 5.0) {
    world.step();
    for (const auto& event : world.takeEvents()) {
      if (event.body == "ball") events.push_back(event);
    }
  }
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, "slip_to_roll");
  EXPECT_NEAR(events[0].t, expected, 1e-12 * expected);
  EXPECT_TRUE(world.takeEvents().empty());
}

TEST(World, ReportsARodRestartAtTheEndOfItsStep) {
  WorldConfig config;
  RodConfig rod;
  rod.params.floor_length = 3.0;  // the text's rod runs past x = 3 in about 1.5 s
  config.bodies.push_back({"rod", rod});
  World world(config);
  Rod unbounded(RodParams{}, rod.initial);
  std::vector<BodyEvent> events;
  while (events.empty() && world.time() < 10.0) {
    world.step();
    unbounded.step(world.dt());
    for (const auto& event : world.takeEvents()) {
      if (event.kind == "restarted") events.push_back(event);
    }
  }
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(findValue(events[0].values, "cause")->text, "lap");
  EXPECT_EQ(events[0].body, "rod");
  EXPECT_DOUBLE_EQ(events[0].t, world.time());
  EXPECT_GT(unbounded.state().x, 3.0);  // the step that took the centre off the floor
  EXPECT_EQ(std::get<Rod>(world.find("rod")->model).state().x, rod.initial.x);
}

TEST(World, ResetReturnsBodiesButNotTime) {
  World world(rodAndBall());
  for (int i = 0; i < 500; ++i) world.step();
  world.reset();
  EXPECT_EQ(world.time(), 0.5);
  const Rod& rod = std::get<Rod>(world.find("rod")->model);
  EXPECT_EQ(rod.state().y, rod.initial().y);
  EXPECT_EQ(rod.state().vy, rod.initial().vy);
  const Roller& ball = std::get<Roller>(world.find("ball")->model);
  EXPECT_EQ(ball.state().v, 3.0);
  EXPECT_EQ(ball.mode(), RollMode::Slipping);
}

TEST(World, UsesTheWorldsGravity) {
  WorldConfig config = rodAndBall();
  config.gravity = 1.62;
  World world(config);
  EXPECT_EQ(std::get<Rod>(world.find("rod")->model).params().gravity, 1.62);
  EXPECT_EQ(std::get<Roller>(world.find("ball")->model).params().gravity, 1.62);
}

TEST(World, RefusesAnInvalidConfig) {
  WorldConfig config = rodAndBall();
  config.publish_rate = 300.0;  // does not divide 1000
  EXPECT_THROW(World{config}, ConfigError);
  config = rodAndBall();
  config.bodies[1].name = "rod";
  EXPECT_THROW(World{config}, ConfigError);
}
