// The sphere of config/slope.yaml on a steeper slope, set through its reconfigure server while the node is
// held at t = 0 (sim.launch start_paused:=true), then stepped 1 s: tan(0.6) = 0.68 is still below the
// sphere's critical 3.5 mu_s = 1.75, so it rolls: x = 5/14 g sin(phi) t^2, and its centre passes the end of
// its slope (L) at t = sqrt(2 L / (5/7 g sin(phi))): the node's `finished` event says when.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include <gtest/gtest.h>
#include <rigid_body_sim/testing/sim_fixture.h>
#include <ros/ros.h>

TEST(Steeper, RollsAsTheClosedFormSays) {
  const rigid_body_sim::SimFixture sim;
  rigid_body_sim::StateLog<rigid_body_sim::RollerState> sphere(sim, "sphere");
  ASSERT_TRUE(sphere.waitConnected());
  rigid_body_sim::EventLog events(sim);
  ASSERT_TRUE(events.waitConnected());
  const double phi = 0.6;
  ASSERT_TRUE(sim.set("sphere", "incline_angle", phi));
  double g = 0.0, rate = 0.0, t = 0.0;
  ASSERT_TRUE(sim.param("gravity", &g));
  ASSERT_TRUE(sim.param("rate", &rate));
  ASSERT_TRUE(sim.step(static_cast<std::uint32_t>(rate), &t));  // 1 simulated second
  rigid_body_sim::RollerState state;
  ASSERT_TRUE(sphere.waitFor(t, &state));
  const double expected = 5.0 / 14.0 * g * std::sin(phi) * state.t * state.t;
  // The node integrates the closed form between events: equal to rounding.
  EXPECT_NEAR(state.x, expected, 1e-9 * std::max(1.0, std::abs(expected))) << "x at t = " << state.t << " s";

  double length = 0.0;
  ASSERT_TRUE(sim.bodyParam("sphere", "incline_length", &length));
  ASSERT_TRUE(sim.step(static_cast<std::uint32_t>(4 * rate)));  // down its slope by t = 3.2 s
  rigid_body_sim::Event finished;
  ASSERT_TRUE(events.waitFor("finished", "sphere", &finished));
  EXPECT_NEAR(finished.t, std::sqrt(2.0 * length / (5.0 / 7.0 * g * std::sin(phi))), 1e-9);
  EXPECT_EQ(rigid_body_sim::eventNumber(finished, "x"), length);  // its state at that instant: on the line
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "steeper_test");
  const ros::NodeHandle node;  // the node stays up (its services and subscriptions) for the tests
  return RUN_ALL_TESTS();
}
