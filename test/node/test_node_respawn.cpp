// sim.launch respawn:=true: sim_node killed with SIGKILL comes back and publishes again, its simulation
// starting afresh (the states' t restarts at 0), and a tf2 listener follows it:
// - wall-clock stamps (use_sim_time false) at real_time_factor 1: the new run's stamps are later than the
//   old ones, so a listener sees nothing special;
// - use_sim_time: /clock and the stamps go back; tf2_ros::TransformListener detects the jump back in time
//   and clears its buffer, and the new transforms are found. The run before the kill (~first_run simulated
//   seconds) is longer than the buffer's 10 s cache, so that a listener that did not clear would refuse the
//   new, older data.
#include <signal.h>

#include <tf2_ros/transform_listener.h>

#include "node_test_util.h"

using namespace rigid_body_sim;
using namespace rigid_body_sim::test;

namespace {

// The process id of a node, asked from the node itself (getPid of its XML-RPC API).
int pidOf(const std::string& node) {
  XmlRpc::XmlRpcValue result;
  return callNode(node, "getPid", result) ? static_cast<int>(result[2]) : -1;
}

}  // namespace

TEST(SimNodeRespawn, KilledNodeComesBackWithFreshTimeAndTfFollows) {
  ros::NodeHandle nh;
  bool sim_time = false;
  ros::param::get("/use_sim_time", sim_time);
  const WorldConfig config = loadWorldConfigFile(configPath());
  World world(config);
  const std::string body = config.bodies.front().name;
  ASSERT_TRUE(std::holds_alternative<RodConfig>(config.bodies.front().config)) << "the test follows a rod";

  tf2_ros::Buffer buffer;  // the default 10 s cache
  tf2_ros::TransformListener listener(buffer);
  StateCollector collector(nh, world);
  ASSERT_TRUE(collector.waitConnected(20.0)) << "the node does not publish every state to this test";
  double first_run = 3.0;
  ros::param::get("~first_run", first_run);
  ASSERT_TRUE(collector.waitFor(
      [&] {
        const auto& rods = collector.rodsLocked()[body];
        return !rods.empty() && rods.back().t >= first_run;
      },
      60.0))
      << "the first run did not reach t = " << first_run << " s";
  const RodState before = collector.rod(body).back();
  std::string error;
  ASSERT_TRUE(buffer.canTransform(config.world_frame, body, ros::Time(0), &error)) << error;

  const int pid = pidOf("/sim");
  ASSERT_GT(pid, 0) << "no pid for /sim";
  ASSERT_EQ(0, kill(pid, SIGKILL));
  collector.clear();

  // The respawned node: the first state whose t is below the last one before the kill starts the new run
  // (a late message of the old node is later than that one).
  auto new_run = [&](const std::vector<RodState>& rods) {
    std::size_t j = 0;
    while (j < rods.size() && rods[j].t >= before.t) ++j;
    return j;
  };
  ASSERT_TRUE(collector.waitFor(
      [&] {
        const auto& rods = collector.rodsLocked()[body];
        return rods.size() >= new_run(rods) + 50;
      },
      60.0))
      << "no state from a respawned node";
  ASSERT_NE(pid, pidOf("/sim")) << "the same process";
  const std::vector<RodState> received = collector.rod(body);
  const std::vector<RodState> after(received.begin() + static_cast<std::ptrdiff_t>(new_run(received)),
                                    received.end());
  EXPECT_LT(after.front().t, 5.0) << "t did not start afresh";
  for (std::size_t j = 1; j < after.size(); ++j) {
    ASSERT_GT(after[j].t, after[j - 1].t) << "time goes back within the new run";
  }
  // The new run is the core World from the config's start again.
  for (const auto& msg : after) {
    while (world.stepCount() < stepIndex(msg.t, config.rate)) world.step();
    expectSameState(expectedRod(world, body), msg, "after the respawn, t = " + std::to_string(msg.t));
  }
  const RodState probe = after.back();
  if (sim_time) {
    ASSERT_LT(probe.header.stamp, before.header.stamp) << "with use_sim_time the stamps go back";
  } else {
    EXPECT_GT(after.front().header.stamp, before.header.stamp) << "wall-clock stamps keep increasing";
  }
  // The listener has the new run's transforms, although (with use_sim_time) they are older than the old
  // run's last ones: it cleared its buffer when time went back.
  ASSERT_TRUE(buffer.canTransform(config.world_frame, body, probe.header.stamp, ros::Duration(5.0), &error))
      << "the TF listener lost track after the respawn: " << error;
  const auto transform = buffer.lookupTransform(config.world_frame, body, probe.header.stamp);
  // The fixed frame too, which the new node sends once on /tf_static (latched).
  EXPECT_TRUE(
      buffer.canTransform(config.world_frame, body + "_floor", ros::Time(0), ros::Duration(5.0), &error))
      << "the static frame is lost after the respawn: " << error;
  EXPECT_NEAR(probe.x, transform.transform.translation.x, 1e-9)
      << "the rod's floor frame runs along the world's x";
}

RBS_ROSTEST_MAIN("test_node_respawn")
