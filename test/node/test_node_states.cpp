// sim_node as fast as possible (real_time_factor 0) for a fixed duration: every state message that arrives
// must be the core World's state at that message's t, exactly, and the messages of each body must follow
// one another at whole multiples of 1 / publish_rate with increasing stamps.
#include "node_test_util.h"

using namespace rigid_body_sim;
using namespace rigid_body_sim::test;

namespace {

// At real_time_factor 0 the node may publish faster than a subscriber drains the publisher's queue, so
// runs of consecutive samples may be separated by gaps: every difference in t must be a whole, positive
// number of publishing periods; most must be exactly one.
template <class Msg>
void checkSequence(const std::vector<Msg>& msgs, double publish_rate, const std::string& name) {
  const double period = 1.0 / publish_rate;
  std::size_t consecutive = 0;
  for (std::size_t j = 1; j < msgs.size(); ++j) {
    EXPECT_GT(msgs[j].header.stamp, msgs[j - 1].header.stamp) << name << " message " << j;
    EXPECT_GT(msgs[j].t, msgs[j - 1].t) << name << " message " << j;
    const double periods = (msgs[j].t - msgs[j - 1].t) / period;
    EXPECT_NEAR(periods, std::round(periods), 1e-6) << name << " message " << j << " t " << msgs[j].t;
    EXPECT_GE(std::round(periods), 1.0) << name << " message " << j << " t " << msgs[j].t;
    if (std::round(periods) == 1.0) ++consecutive;
    // Stamps follow t: one period of t is one period of stamp.
    EXPECT_NEAR((msgs[j].header.stamp - msgs[j - 1].header.stamp).toSec(), msgs[j].t - msgs[j - 1].t, 1e-6)
        << name << " message " << j;
  }
  EXPECT_GT(consecutive, msgs.size() / 2) << name << ": too few consecutive samples";
  ROS_INFO("%s: %zu messages, %zu consecutive pairs, t from %.2f to %.2f", name.c_str(), msgs.size(),
           consecutive, msgs.front().t, msgs.back().t);
}

}  // namespace

TEST(SimNodeStates, EveryStateIsTheCorePrediction) {
  ros::NodeHandle nh;
  const WorldConfig config = loadWorldConfigFile(configPath());
  World world(config);
  const double rate = config.rate;
  const std::int64_t steps_per_publish = std::llround(config.rate / config.publish_rate);

  StateCollector collector(nh, world);
  NodeLog log(nh);
  ASSERT_TRUE(collector.waitConnected(10.0)) << "no publisher of the state topics";
  ASSERT_TRUE(log.waitConnected(10.0)) << "the node does not log to this test";
  // The node starts paused: at real_time_factor 0 its whole run could be over before this test subscribes.
  ASSERT_TRUE(ros::service::waitForService("/sim/unpause", 10000));
  ASSERT_TRUE(callEmpty("/sim/unpause"));
  // The run is over when the node says so, after it published the last sample (t = duration). Collect
  // until that sample of every body has come, or the node has gone: at real_time_factor 0 a subscriber on
  // a busy machine falls behind, and what the node's queues still hold when it shuts down (half a second
  // later) is lost, as ROS drops what a subscriber cannot take.
  double duration = 0.0;
  ASSERT_TRUE(ros::param::get("/sim/duration", duration));
  ASSERT_TRUE(log.takeUntil("the requested duration; shutting down", 40.0)) << "the run did not end";
  const std::optional<bool> complete = collector.waitAllAtOrGone(world, duration, 40.0);
  ASSERT_TRUE(complete.has_value()) << "neither every body's state at t = " << duration
                                    << " nor the node's exit";
  if (!*complete) ROS_WARN("the node shut down before this test had every body's state at t = %g", duration);

  // Index the messages by step count; check the per-body sequences.
  std::map<std::string, std::map<std::int64_t, RodState>> rods;
  std::map<std::string, std::map<std::int64_t, RollerState>> rollers;
  std::int64_t max_step = 0;
  // Checks one body's sequence and indexes its messages by step count (rods and rollers alike).
  auto index = [&](const std::string& name, const auto& msgs, auto& by_step) {
    ASSERT_GE(msgs.size(), 50u) << name;
    checkSequence(msgs, config.publish_rate, name);
    for (const auto& msg : msgs) {
      const std::int64_t n = stepIndex(msg.t, rate);
      EXPECT_EQ(0, n % steps_per_publish) << name << " t " << msg.t << " is not a publishing instant";
      EXPECT_EQ(static_cast<double>(n) / rate, msg.t) << name;
      by_step[n] = msg;
      max_step = std::max(max_step, n);
    }
  };
  for (const auto& body : world.bodies()) {
    if (std::holds_alternative<Rod>(body.model)) {
      index(body.name, collector.rod(body.name), rods[body.name]);
    } else {
      index(body.name, collector.roller(body.name), rollers[body.name]);
    }
  }
  // No sample beyond the requested duration.
  EXPECT_LE(max_step, std::llround(duration * rate)) << "a sample after the requested duration";

  // Step the core World along and compare every received message at its step.
  std::size_t compared = 0;
  for (std::int64_t n = 0; n <= max_step; ++n) {
    if (n > 0) world.step();
    if (n % steps_per_publish != 0) continue;
    for (auto& [name, by_step] : rods) {
      auto it = by_step.find(n);
      if (it == by_step.end()) continue;
      expectSameState(expectedRod(world, name), it->second, name + " at step " + std::to_string(n));
      ++compared;
    }
    for (auto& [name, by_step] : rollers) {
      auto it = by_step.find(n);
      if (it == by_step.end()) continue;
      expectSameState(expectedRoller(world, name), it->second, name + " at step " + std::to_string(n));
      ++compared;
    }
    // Stop at the first mismatching instant rather than print thousands of lines.
    if (::testing::Test::HasFailure()) break;
  }
  EXPECT_GT(compared, 0u);
  ROS_INFO("compared %zu state messages up to step %lld", compared, static_cast<long long>(max_step));
}

RBS_ROSTEST_MAIN("test_node_states")
