// The node's services (ros/node_services.h) under rostest's master, without sim_node (node_services.test):
// the test is the node. Each request of ~spawn, ~delete, ~set_state and ~reset reaches its one path for
// every change as the command the request asks for, built from the running world (a request that does not
// parse is refused there, in the answer's one line); the response carries the answer; ~get_config,
// ~pause, ~unpause and ~step hand their work over.
#include <rigid_body_sim/Delete.h>
#include <rigid_body_sim/GetConfig.h>
#include <rigid_body_sim/SetState.h>
#include <rigid_body_sim/Spawn.h>

#include "node_test_util.h"
#include "rigid_body_sim/io/config_writer.h"
#include "rigid_body_sim/ros/node_services.h"
#include "test_util.h"

using namespace rigid_body_sim;

namespace {

// What the node's side was asked, and answers as the node does: a change applies to `world` or is refused.
struct FakeNode {
  World world{loadWorldConfigFile(test::config("demo.yaml"))};
  std::mutex mutex;
  std::vector<std::string> kinds_asked;
  std::vector<WorldCommand> applied;
  std::vector<bool> pauses;
  std::vector<std::uint64_t> steps;

  ChangeAnswer change(const std::string& kind, const std::string& body, const BuildCommand& build) {
    std::lock_guard<std::mutex> lock(mutex);
    kinds_asked.push_back(kind + " " + body);
    ChangeAnswer answer;
    try {
      answer.command = build(world);
      world.apply(*answer.command);
      applied.push_back(*answer.command);
      answer.accepted = true;
      answer.why = "ok";
    } catch (const ConfigError& error) {
      answer.command.reset();
      answer.why = std::string("refused: ") + error.what();
    }
    answer.t = 1.25;
    answer.config = world.config();
    return answer;
  }
};

TEST(NodeServices, HandEachRequestToTheNode) {
  FakeNode node;
  const NodeServices services(ros::NodeHandle("/sim"),
                              {[&](const std::string& kind, const std::string& body,
                                   const BuildCommand& build) { return node.change(kind, body, build); },
                               [&] {
                                 std::lock_guard<std::mutex> lock(node.mutex);
                                 return node.world.config();
                               },
                               [&](bool paused) {
                                 std::lock_guard<std::mutex> lock(node.mutex);
                                 node.pauses.push_back(paused);
                               },
                               [&](std::uint64_t steps, Step::Response& response) {
                                 std::lock_guard<std::mutex> lock(node.mutex);
                                 node.steps.push_back(steps);
                                 response.success = steps == 5;
                                 response.message = steps == 5 ? "ok" : "refused: not 5";
                                 response.t = 0.5;
                               }});
  ASSERT_TRUE(ros::service::waitForService("/sim/step", 10000));

  Spawn spawn;
  spawn.request.name = "ball";
  spawn.request.body = "{type: roller, shape: ring}";
  ASSERT_TRUE(test::serviceCalls().call("/sim/spawn", spawn));
  EXPECT_TRUE(spawn.response.success);
  EXPECT_EQ(spawn.response.message, "ok");
  EXPECT_EQ(spawn.response.t, 1.25) << "the time the node says it applied at";
  ASSERT_EQ(node.applied.size(), 1u);
  EXPECT_EQ(node.applied[0].kind, WorldCommand::Kind::Spawn);
  EXPECT_EQ(toYaml(node.applied[0].config), toYaml(parseBodyText("ball", spawn.request.body)));

  Spawn bad;
  bad.request.name = "cube";
  bad.request.body = "{type: cube}";
  ASSERT_TRUE(test::serviceCalls().call("/sim/spawn", bad));
  EXPECT_FALSE(bad.response.success);
  EXPECT_EQ(bad.response.message.rfind("refused: ", 0), 0u) << bad.response.message;
  EXPECT_NE(bad.response.message.find("cube"), std::string::npos) << bad.response.message;

  SetState set_state;
  set_state.request.name = "rod";
  set_state.request.state = "{y: 2.5}";
  ASSERT_TRUE(test::serviceCalls().call("/sim/set_state", set_state));
  EXPECT_TRUE(set_state.response.success) << set_state.response.message;
  ASSERT_EQ(node.applied.size(), 2u);
  EXPECT_EQ(toYaml(node.applied[1].state), toYaml(parseStateText("rod", "{y: 2.5}")));

  Delete remove;
  remove.request.name = "cylinder";
  ASSERT_TRUE(test::serviceCalls().call("/sim/delete", remove));
  EXPECT_TRUE(remove.response.success);
  EXPECT_TRUE(test::callEmpty("/sim/reset"));
  EXPECT_EQ(node.kinds_asked, (std::vector<std::string>{"spawn ball", "spawn cube", "set_state rod",
                                                        "delete cylinder", "reset "}));
  ASSERT_EQ(node.applied.size(), 4u);
  EXPECT_EQ(node.applied[2].kind, WorldCommand::Kind::Delete);
  EXPECT_EQ(node.applied[3].kind, WorldCommand::Kind::Reset);

  GetConfig get_config;
  ASSERT_TRUE(test::serviceCalls().call("/sim/get_config", get_config));
  EXPECT_EQ(get_config.response.yaml, toYaml(node.world.config())) << "the world as it runs";

  EXPECT_TRUE(test::callEmpty("/sim/pause"));
  EXPECT_TRUE(test::callEmpty("/sim/unpause"));
  EXPECT_EQ(node.pauses, (std::vector<bool>{true, false}));
  bool called = false;
  EXPECT_TRUE(test::callStep(5, &called).response.success);
  EXPECT_FALSE(test::callStep(0, &called).response.success);
  EXPECT_EQ(node.steps, (std::vector<std::uint64_t>{5, 0}));
}

}  // namespace

RBS_ROSTEST_MAIN("test_node_node_services")
