// The NaN guard end to end (guard.test): sim_node_faults, the node built with a fault injected where the
// guard looks (test/faults/fault_injection.h), runs demo.yaml and makes body ~fault_body's x NaN in the step
// to ~fault_time. Through the node's publishing path: one ERROR line, the one docs/reliability.md shows; that
// body published at its last finite state from then on, every field finite; every other body the core
// World's at every state, as if nothing had happened.
#include <fstream>
#include <sstream>
#include <type_traits>

#include "node_test_util.h"
#include "rigid_body_sim/run/finite_guard.h"

using namespace rigid_body_sim;
using namespace rigid_body_sim::test;

namespace {

std::string privateParam(const std::string& name) {
  std::string value;
  ros::param::get("~" + name, value);
  return value;
}

// Every state of body `name` as the core World has it at the same step, or, from `fault_step` on, as the
// guard holds it: its state after the step before, at the message's t.
template <class Msg>
std::size_t expectWorldOrHeld(const std::vector<Msg>& got, const WorldConfig& config, const std::string& name,
                              std::int64_t fault_step) {
  World world(config);
  std::optional<Body> held;
  std::size_t compared = 0;
  for (const Msg& msg : got) {
    const std::int64_t n = stepIndex(msg.t, config.rate);
    while (world.stepCount() < std::min(n, fault_step - 1)) world.step();
    if (n >= fault_step && !held) held = *world.find(name);
    const Body& expected = held ? *held : *world.find(name);
    Msg want;
    if constexpr (std::is_same_v<Msg, RodState>) {
      want = toStateMsg(msg.t, std::get<Rod>(expected.model));
    } else {
      want = toStateMsg(msg.t, std::get<Roller>(expected.model));
    }
    expectSameState(want, msg, name + " at t = " + std::to_string(msg.t));
    ++compared;
    if (::testing::Test::HasFailure()) break;
  }
  return compared;
}

}  // namespace

TEST(SimNodeGuard, HoldsTheFaultyBodyAndRunsTheOthersOn) {
  ros::NodeHandle nh;
  const WorldConfig config = loadWorldConfigFile(privateParam("config"));
  const std::string faulty = privateParam("fault_body");
  double fault_time = 0.0;
  ASSERT_TRUE(ros::param::get("~fault_time", fault_time));
  const auto fault_step = static_cast<std::int64_t>(std::ceil(fault_time * config.rate));
  World world(config);
  ASSERT_TRUE(world.find(faulty)) << faulty;

  StateCollector collector(nh, world);
  NodeLog log(nh);
  double duration = 0.0;
  std::vector<rosgraph_msgs::Log> logged;
  ASSERT_NO_FATAL_FAILURE(runToDuration(collector, log, world, &duration, &logged));
  ASSERT_GT(duration, fault_time);

  // The one ERROR line: the body, the quantity, the step, and what it ran with at its last finite state.
  while (world.stepCount() < fault_step - 1) world.step();
  const std::string expected_error =
      "body '" + faulty + "': x became non-finite in the step to t = " + formatNumber(fault_time) +
      " s; the body is paused at its last finite state, the others go on (a reconfigure of it or ~reset "
      "restarts it). It ran with: " +
      describeBody(*world.find(faulty));
  const auto errors = textsAtLeast(logged, rosgraph_msgs::Log::ERROR);
  ASSERT_EQ(errors.size(), 1u) << "one ERROR line, the guard's";
  EXPECT_EQ(errors[0], expected_error);

  // Every state of every body, from the first after the start to the duration.
  std::size_t compared = 0;
  for (const auto& body : world.bodies()) {
    const std::int64_t body_fault =
        body.name == faulty ? fault_step : std::numeric_limits<std::int64_t>::max();
    compared += std::holds_alternative<Rod>(body.model)
                    ? expectWorldOrHeld(collector.rod(body.name), config, body.name, body_fault)
                    : expectWorldOrHeld(collector.roller(body.name), config, body.name, body_fault);
  }
  const std::size_t samples = static_cast<std::size_t>(std::llround(duration * config.publish_rate));
  EXPECT_GE(compared, world.bodies().size() * samples) << "a state missing";

  // docs/reliability.md shows that very line.
  std::ifstream doc(privateParam("doc"));
  ASSERT_TRUE(doc) << privateParam("doc");
  std::stringstream text;
  text << doc.rdbuf();
  EXPECT_NE(text.str().find("\n" + expected_error + "\n"), std::string::npos)
      << "docs/reliability.md does not show the guard's line of this run:\n"
      << expected_error;
  ROS_INFO("compared %zu states; the guard's line: %s", compared, expected_error.c_str());
}

RBS_ROSTEST_MAIN("test_node_guard")
