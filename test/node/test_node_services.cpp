// sim_node at wall pace: ~pause, ~step, ~reset and ~unpause, checked against the core World.
#include <tf2_msgs/TFMessage.h>

#include <chrono>
#include <cstdio>

#include "node_test_util.h"

using namespace rigid_body_sim;
using namespace rigid_body_sim::test;

namespace {

double latestRodT(StateCollector& c) {
  const auto msgs = c.rod("rod");
  return msgs.empty() ? -1.0 : msgs.back().t;
}

// Waits for a state of `body` with exactly time t; returns whether it came.
bool waitRodAt(StateCollector& c, double t, RodState* out, double timeout = 3.0) {
  bool found = false;
  c.waitFor(
      [&] {
        for (const auto& m : c.rodsLocked()["rod"]) {
          if (m.t == t) {
            *out = m;
            found = true;
          }
        }
        return found;
      },
      timeout);
  return found;
}

bool waitRollerAt(StateCollector& c, const std::string& name, double t, RollerState* out,
                  double timeout = 3.0) {
  bool found = false;
  c.waitFor(
      [&] {
        for (const auto& m : c.rollersLocked()[name]) {
          if (m.t == t) {
            *out = m;
            found = true;
          }
        }
        return found;
      },
      timeout);
  return found;
}

}  // namespace

TEST(SimNodeServices, PauseStepResetUnpause) {
  ros::NodeHandle nh;
  const WorldConfig config = loadWorldConfigFile(configPath());
  const World initial_world(config);
  const double dt = 1.0 / config.rate;

  StateCollector c(nh, initial_world);
  // Every transform on /tf: per frame, stamps strictly increasing through pause, step, reset and unpause.
  std::mutex tf_mutex;
  std::map<std::string, std::vector<ros::Time>> tf_stamps;
  ros::Subscriber tf_sub =
      nh.subscribe<tf2_msgs::TFMessage>("/tf", 10000, [&](const tf2_msgs::TFMessage::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(tf_mutex);
        for (const auto& tf : m->transforms) tf_stamps[tf.child_frame_id].push_back(tf.header.stamp);
      });
  ASSERT_TRUE(c.waitConnected(10.0));
  ASSERT_TRUE(ros::service::waitForService("/sim/step", 10000));
  ASSERT_TRUE(c.waitFor([&] { return c.rodsLocked()["rod"].size() >= 5; }, 5.0)) << "no rod states";

  // --- pause, and step(1): it gives the current time (the world may be between two publishing instants)
  // and publishes every body's state at it. Those states are the last before the pause's silence, and each
  // topic delivers in order: once they have come, everything published before has come too.
  const double t_before_pause = latestRodT(c);
  ASSERT_TRUE(callEmpty("/sim/pause"));
  bool called = false;
  Step s1 = callStep(1, &called);
  ASSERT_TRUE(called);
  ASSERT_TRUE(s1.response.success) << s1.response.message;
  EXPECT_GE(s1.response.t, t_before_pause + dt - 1e-9);
  ASSERT_TRUE(c.waitAllAt(initial_world, s1.response.t))
      << "no state of every body at t = " << s1.response.t << " after step(1)";
  RodState rod_msg;
  ASSERT_TRUE(waitRodAt(c, s1.response.t, &rod_msg));

  // --- paused: nothing comes but what the next step publishes. The rod's topic delivers in order, so once
  // that step's last state has come, anything published while paused has come before it.
  EXPECT_EQ(s1.response.t, latestRodT(c));
  const std::size_t rods_paused = c.rod("rod").size();

  // --- step(10): t advances by exactly 10 dt and the state at that t is published for every body
  Step s10 = callStep(10, &called);
  ASSERT_TRUE(called);
  ASSERT_TRUE(s10.response.success) << s10.response.message;
  EXPECT_NEAR(s10.response.t, s1.response.t + 10 * dt, 1e-9);
  EXPECT_TRUE(waitRodAt(c, s10.response.t, &rod_msg)) << "no rod state at t = " << s10.response.t;
  {
    // Since the pause: the publishing instants inside the step, then its end, each once, nothing else.
    const std::int64_t from = stepIndex(s1.response.t, config.rate),
                       to = stepIndex(s10.response.t, config.rate);
    const auto per_sample = static_cast<std::int64_t>(std::llround(config.rate / config.publish_rate));
    std::vector<double> expected;
    for (std::int64_t i = from + 1; i < to; ++i) {
      if (i % per_sample == 0) expected.push_back(static_cast<double>(i) / config.rate);
    }
    expected.push_back(s10.response.t);
    const auto rods = c.rod("rod");
    std::vector<double> since_pause;
    for (std::size_t i = rods_paused; i < rods.size(); ++i) since_pause.push_back(rods[i].t);
    EXPECT_EQ(since_pause, expected) << "states came while paused, or a step's went missing";
  }
  for (const auto& body : initial_world.bodies()) {
    if (std::holds_alternative<Roller>(body.model)) {
      RollerState roller_msg;
      EXPECT_TRUE(waitRollerAt(c, body.name, s10.response.t, &roller_msg)) << body.name;
    }
  }
  // The state published by a step is the core World at that step count (nothing else happened yet).
  {
    World world(config);
    const std::int64_t n = stepIndex(s10.response.t, config.rate);
    for (std::int64_t i = 0; i < n; ++i) world.step();
    expectSameState(expectedRod(world, "rod"), rod_msg, "rod after step(10)");
  }

  // --- out-of-range steps are refused, the time stays, the node still answers
  Step s0 = callStep(0, &called);
  ASSERT_TRUE(called);
  EXPECT_FALSE(s0.response.success);
  EXPECT_FALSE(s0.response.message.empty());
  EXPECT_EQ(s10.response.t, s0.response.t) << "a refused step changed the time";
  Step sbig = callStep(1000000000u, &called);
  ASSERT_TRUE(called) << "node died on step(1e9)";
  EXPECT_FALSE(sbig.response.success);
  EXPECT_EQ(s10.response.t, sbig.response.t);
  Step s_alive = callStep(1, &called);
  ASSERT_TRUE(called) << "node no longer answers";
  EXPECT_TRUE(s_alive.response.success) << s_alive.response.message;
  EXPECT_NEAR(s_alive.response.t, s10.response.t + dt, 1e-9);
  const double t_before_reset = s_alive.response.t;
  // Everything published so far has arrived before the reset's states are looked at.
  ASSERT_TRUE(c.waitAllAt(initial_world, t_before_reset))
      << "no state of every body at t = " << t_before_reset;

  // --- reset (paused): nothing is published at the same t (a state there was already published); the next
  // step shows it: step(1) and step(5) after it equal a fresh World after 1 and 6 steps. Time never goes
  // back.
  c.clear();
  ASSERT_TRUE(callEmpty("/sim/reset"));
  Step after_reset = callStep(1, &called);
  ASSERT_TRUE(called);
  ASSERT_TRUE(after_reset.response.success);
  EXPECT_NEAR(after_reset.response.t, t_before_reset + dt, 1e-9);
  ASSERT_TRUE(c.waitAllAt(initial_world, after_reset.response.t))
      << "no state of every body after reset and step(1)";
  {
    World world(config);
    world.step();
    const auto rods = c.rod("rod");
    for (const auto& m : rods) EXPECT_NE(m.t, t_before_reset) << "a second state at the reset's t";
    expectSameState(toStateMsg(after_reset.response.t, std::get<Rod>(world.find("rod")->model)), rods.back(),
                    "rod 1 step after reset");
    for (const auto& body : world.bodies()) {
      if (!std::holds_alternative<Roller>(body.model)) continue;
      const auto rollers = c.roller(body.name);
      ASSERT_FALSE(rollers.empty()) << body.name;
      expectSameState(toStateMsg(after_reset.response.t, std::get<Roller>(body.model)), rollers.back(),
                      body.name + " 1 step after reset");
    }
  }
  Step s5 = callStep(5, &called);
  ASSERT_TRUE(called);
  ASSERT_TRUE(s5.response.success);
  EXPECT_NEAR(s5.response.t, t_before_reset + 6 * dt, 1e-9);
  ASSERT_TRUE(waitRodAt(c, s5.response.t, &rod_msg));
  {
    World world(config);
    for (int i = 0; i < 6; ++i) world.step();
    const Rod& rod = std::get<Rod>(world.find("rod")->model);
    expectSameState(toStateMsg(s5.response.t, rod), rod_msg, "rod 6 steps after reset");
  }

  // --- unpause: time advances again at wall pace; ~step is refused while running. The node anchors its
  // pace when it unpauses, so a state received at wall time w is at most w - (the wall time before the
  // call) past t_unpaused: never ahead of the wall clock, whatever the load. Behind it, a state arrives at
  // most kMaxLag after its time on the wall clock (the pace the README promises at real_time_factor 1,
  // as a subscriber on the same machine receives it, one core kept busy); StepPacer's own test checks the
  // pace exactly.
  constexpr double kMaxLag = 0.25;  // s
  const double t_unpaused = s5.response.t;
  const auto before_unpause = std::chrono::steady_clock::now();  // the node's pacer's clock
  const auto wall_since_unpause = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - before_unpause).count();
  };
  ASSERT_TRUE(callEmpty("/sim/unpause"));
  Step running = callStep(1, &called);
  ASSERT_TRUE(called);
  EXPECT_FALSE(running.response.success) << "step accepted while running";
  double ahead = -1e9;  // the most any received state was ahead of the wall clock (s)
  double behind = 0.0;  // the most the last received state was behind it, the first second of states
  const bool kept_up = c.waitFor(
      [&] {
        const auto& rods = c.rodsLocked()["rod"];
        const double wall = wall_since_unpause();
        if (rods.empty() || rods.back().t <= t_unpaused) {
          behind = std::max(behind, wall);
          return false;
        }
        ahead = std::max(ahead, rods.back().t - t_unpaused - wall);
        behind = std::max(behind, wall - (rods.back().t - t_unpaused));
        return rods.back().t >= t_unpaused + 1.0;
      },
      20.0);
  EXPECT_TRUE(kept_up) << "time does not advance after unpause";
  EXPECT_LE(ahead, 1e-3) << "the node ran ahead of the wall clock";
  EXPECT_LE(behind, kMaxLag) << "a state came more than " << kMaxLag << " s after its time on the wall clock";
  std::printf("one simulated second after unpause took %.3f wall seconds, at most %.3f s behind\n",
              wall_since_unpause(), behind);

  tf_sub.shutdown();
  std::lock_guard<std::mutex> lock(tf_mutex);
  EXPECT_EQ(initial_world.bodies().size(), tf_stamps.size()) << "a body without transforms on /tf";
  for (const auto& [frame, stamps] : tf_stamps) {
    for (std::size_t j = 1; j < stamps.size(); ++j) {
      ASSERT_GT(stamps[j], stamps[j - 1])
          << frame << ": transform " << j << " repeats or goes back (TF_REPEATED_DATA)";
    }
  }
}

RBS_ROSTEST_MAIN("test_node_services")
