// sim_node at ten times wall pace for a fixed duration (states.test): every state from the start to the
// duration arrives, each the core World's state at that message's t, exactly, one publishing period after
// the one before, with increasing stamps. The pace is one a subscriber keeps up with on a busy machine: as
// fast as possible the node outruns any subscriber, and drops the oldest of what its queue for a subscriber
// holds (docs/performance.md).
#include "node_test_util.h"

using namespace rigid_body_sim;
using namespace rigid_body_sim::test;

namespace {

// Every publishing instant from the first after t = 0 (the node published t = 0 at its start, paused, which
// this test may have subscribed after) to the duration, each one period after the one before.
template <class Msg>
void checkSequence(const std::vector<Msg>& msgs, double publish_rate, double duration,
                   const std::string& name) {
  const double period = 1.0 / publish_rate;
  ASSERT_FALSE(msgs.empty()) << name;
  EXPECT_LE(msgs.front().t, period) << name << ": the first state after the start is missing";
  EXPECT_EQ(duration, msgs.back().t) << name << ": the last state is not at the duration";
  std::size_t consecutive = 0;
  for (std::size_t j = 1; j < msgs.size(); ++j) {
    EXPECT_GT(msgs[j].header.stamp, msgs[j - 1].header.stamp) << name << " message " << j;
    const double periods = (msgs[j].t - msgs[j - 1].t) / period;
    EXPECT_NEAR(1.0, periods, 1e-6) << name << " message " << j << " t " << msgs[j].t
                                    << ": a state is missing";
    if (std::round(periods) == 1.0) ++consecutive;
    // Stamps follow t: one period of t is one period of stamp.
    EXPECT_NEAR((msgs[j].header.stamp - msgs[j - 1].header.stamp).toSec(), msgs[j].t - msgs[j - 1].t, 1e-6)
        << name << " message " << j;
  }
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
  double duration = 0.0;
  ASSERT_NO_FATAL_FAILURE(runToDuration(collector, log, world, &duration));

  // Index the messages by step count; check the per-body sequences.
  std::map<std::string, std::map<std::int64_t, RodState>> rods;
  std::map<std::string, std::map<std::int64_t, RollerState>> rollers;
  std::int64_t max_step = 0;
  // Checks one body's sequence and indexes its messages by step count (rods and rollers alike).
  auto index = [&](const std::string& name, const auto& msgs, auto& by_step) {
    checkSequence(msgs, config.publish_rate, duration, name);
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
