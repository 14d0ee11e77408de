// sim_node's world changes against the core: ~spawn, ~set_state and ~delete while paused equal a World given
// the same commands at the same step; ~get_config loads as a config; ~commands numbers them from the config.
// A table of bad requests: each refused in one line, nothing changes, nothing on ~commands. Spawns while the
// world runs answer the t of their ~commands entry.
#include <algorithm>
#include <limits>

#include "node_test_util.h"
#include "rigid_body_sim/Command.h"
#include "rigid_body_sim/Delete.h"
#include "rigid_body_sim/GetConfig.h"
#include "rigid_body_sim/SetState.h"
#include "rigid_body_sim/Spawn.h"
#include "rigid_body_sim/core/node_interface.h"
#include "rigid_body_sim/io/config_writer.h"
#include "test_util.h"

using namespace rigid_body_sim;
using namespace rigid_body_sim::test;

namespace {

struct BadRequest {
  std::string service;  // spawn, delete or set_state
  std::string name;
  std::string yaml;  // the body (spawn) or the state (set_state)
};

// The bad requests, one per row: what is refused and why is in each row's comment.
const std::vector<BadRequest>& badRequests() {
  static const std::vector<BadRequest> rows = {
      {"spawn", "hoop", "{type: roller"},                         // YAML syntax
      {"spawn", "hoop", "[1, 2]"},                                // not a map
      {"spawn", "hoop", ""},                                      // empty body
      {"spawn", "hoop", "{shape: ring}"},                         // no type
      {"spawn", "hoop", "{type: wheel}"},                         // unknown type
      {"spawn", "hoop", "{type: roller, colour: red}"},           // unknown key
      {"spawn", "hoop", "{type: roller, mass: -1}"},              // out of range
      {"spawn", "hoop", "{type: roller, mass: .nan}"},            // NaN
      {"spawn", "hoop", "{type: roller, mu_d: 0.5, mu_s: 0.1}"},  // relation
      {"spawn", "hoop", "{type: roller, x0: 99}"},                // off the slope
      {"spawn", "hoop", "{type: rod, mass: abc}"},                // not a number
      {"spawn", "rod", "{type: rod}"},                            // duplicate
      {"spawn", "markers", "{type: rod}"},                        // reserved (a topic)
      {"spawn", "spawn", "{type: rod}"},                          // reserved (a service)
      {"spawn", "rate", "{type: rod}"},                           // reserved (a world key)
      {"spawn", "world", "{type: rod}"},                          // the world frame
      {"spawn", "rod_floor", "{type: rod}"},                      // another body's fixed frame
      {"spawn", "9lives", "{type: rod}"},                         // invalid name
      {"spawn", "", "{type: rod}"},                               // empty name
      {"spawn", "a/b", "{type: rod}"},                            // not a graph name
      {"spawn", "hoop", "{type: roller}\n---\n{type: rod}"},      // two YAML documents
      {"delete", "nobody", ""},                                   // unknown body
      {"delete", "", ""},                                         // empty name
      {"set_state", "nobody", "{x: 1}"},                          // unknown body
      {"set_state", "rod", "{v: 1}"},                             // a roller's field
      {"set_state", "sphere", "{y: 1}"},                          // a rod's field
      {"set_state", "rod", "{energy: 1}"},                        // derived, not settable
      {"set_state", "rod", "{x: .nan}"},                          // NaN
      {"set_state", "rod", "{vx: 1e9}"},                          // out of range
      {"set_state", "sphere", "{x: -1}"},                         // off the slope
      {"set_state", "rod", "{}"},                                 // no field
      {"set_state", "rod", ""},                                   // empty
      {"set_state", "rod", "{x: [1]}"},                           // not a number
      {"set_state", "rod", "{x: 1"},                              // YAML syntax
      {"set_state", "rod", "{x: 1}\n---\n{x: 2}"},                // two YAML documents
  };
  return rows;
}

}  // namespace

// docs/testing.md counts the rows above.
TEST(SimNodeCommands, TheDocsCountTheBadRequestsThereAre) {
  const std::string docs = slurp(fs::path(RBS_README).parent_path() / "docs" / "testing.md");
  const std::string count = std::to_string(badRequests().size()) + " bad requests, each refused in one line";
  EXPECT_NE(docs.find(count), std::string::npos) << "docs/testing.md should say " << count;
}

namespace {

std::pair<bool, std::string> call(const BadRequest& request) {
  if (request.service == "spawn") {
    Spawn srv;
    srv.request.name = request.name;
    srv.request.body = request.yaml;
    EXPECT_TRUE(serviceCalls().call("/sim/spawn", srv));
    return {srv.response.success, srv.response.message};
  }
  if (request.service == "delete") {
    Delete srv;
    srv.request.name = request.name;
    EXPECT_TRUE(serviceCalls().call("/sim/delete", srv));
    return {srv.response.success, srv.response.message};
  }
  SetState srv;
  srv.request.name = request.name;
  srv.request.state = request.yaml;
  EXPECT_TRUE(serviceCalls().call("/sim/set_state", srv));
  return {srv.response.success, srv.response.message};
}

std::string getConfig() {
  GetConfig srv;
  EXPECT_TRUE(serviceCalls().call("/sim/get_config", srv));
  return srv.response.yaml;
}

// Every message on ~commands from the subscription on: the latched one first.
class Commands {
 public:
  explicit Commands(ros::NodeHandle& nh)
      : sub_(nh.subscribe<rigid_body_sim::Command>("/sim/commands", 1000,
                                                   [this](const rigid_body_sim::Command::ConstPtr& msg) {
                                                     std::lock_guard<std::mutex> lock(mutex_);
                                                     received_.push_back(*msg);
                                                     arrived_.notify_all();
                                                   })) {}
  std::vector<rigid_body_sim::Command> received() {
    std::lock_guard<std::mutex> lock(mutex_);
    return received_;
  }
  // Waits until `count` messages have come, at most 10 wall seconds.
  bool waitCount(std::size_t count) {
    std::unique_lock<std::mutex> lock(mutex_);
    return arrived_.wait_for(lock, std::chrono::seconds(10), [&] { return received_.size() >= count; });
  }

 private:
  std::mutex mutex_;
  std::condition_variable arrived_;
  std::vector<rigid_body_sim::Command> received_;
  ros::Subscriber sub_;
};

WorldCommand commandOf(WorldCommand::Kind kind, const World& world, const std::string& body) {
  WorldCommand command;
  command.kind = kind;
  command.step = world.stepCount();
  command.body = body;
  return command;
}

}  // namespace

TEST(SimNodeCommands, ChangesEqualTheCoreAndBadRequestsChangeNothing) {
  ros::NodeHandle nh;
  const WorldConfig config = loadWorldConfigFile(configPath());
  Commands commands(nh);
  ASSERT_TRUE(commands.waitCount(1)) << "no latched config on ~commands";
  EXPECT_EQ(commands.received()[0].kind, "config");
  EXPECT_EQ(commands.received()[0].header.seq, 0u);
  // The node's world, command for command: the config file's (its bodies in the parameter server's order).
  World world(parseWorldConfigText(commands.received()[0].yaml, "~commands"), node_interface::ownNames());
  EXPECT_EQ(toYaml(World(config).config()).size(), commands.received()[0].yaml.size());

  ASSERT_TRUE(callEmpty("/sim/pause"));
  bool called = false;
  const Step paused = callStep(1, &called);
  ASSERT_TRUE(called && paused.response.success) << paused.response.message;
  const std::int64_t count = stepIndex(paused.response.t, config.rate);
  while (world.stepCount() < count) world.step();

  // --- the bad requests
  const std::string before = getConfig();
  EXPECT_EQ(before, toYaml(world.config()));
  for (const auto& request : badRequests()) {
    const auto [success, message] = call(request);
    EXPECT_FALSE(success) << request.service << " " << request.name << " " << request.yaml;
    EXPECT_EQ(message.rfind("refused ", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  EXPECT_EQ(getConfig(), before) << "a refused request changed the config";
  StateCollector c(nh, world);
  ASSERT_TRUE(c.waitConnected(10.0));
  Step s1 = callStep(1, &called);
  ASSERT_TRUE(called && s1.response.success);
  world.step();
  ASSERT_TRUE(c.waitAllAt(world, s1.response.t));
  expectSameState(expectedRod(world, "rod"), c.rod("rod").back(), "rod after the bad requests");
  for (const auto& body : world.bodies()) {
    if (std::holds_alternative<Roller>(body.model)) {
      expectSameState(expectedRoller(world, body.name), c.roller(body.name).back(), body.name);
    }
  }
  EXPECT_EQ(commands.received().size(), 1u) << "a refused request was published on ~commands";

  // --- spawn, set_state, delete while paused: each applies at the current step, shows with the next
  Spawn spawn;
  spawn.request.name = "hoop";
  spawn.request.body = "{type: roller, shape: ring, incline_angle: 0.4, x0: 0.5}";
  ASSERT_TRUE(serviceCalls().call("/sim/spawn", spawn));
  ASSERT_TRUE(spawn.response.success) << spawn.response.message;
  WorldCommand spawned = commandOf(WorldCommand::Kind::Spawn, world, "hoop");
  spawned.config = parseBodyText("hoop", spawn.request.body);
  world.apply(spawned);

  SetState set;
  set.request.name = "rod";
  set.request.state = "{y: 2.5, omega: -1.5}";
  ASSERT_TRUE(serviceCalls().call("/sim/set_state", set));
  ASSERT_TRUE(set.response.success) << set.response.message;
  WorldCommand moved = commandOf(WorldCommand::Kind::SetState, world, "rod");
  moved.state = {{"y", 2.5}, {"omega", -1.5}};
  world.apply(moved);

  Delete del;
  del.request.name = "cylinder";
  ASSERT_TRUE(serviceCalls().call("/sim/delete", del));
  ASSERT_TRUE(del.response.success) << del.response.message;
  world.apply(commandOf(WorldCommand::Kind::Delete, world, "cylinder"));

  EXPECT_EQ(getConfig(), toYaml(world.config()));
  EXPECT_NO_THROW(parseWorldConfigText(getConfig(), "get_config"));

  StateCollector after(nh, world);
  ASSERT_TRUE(after.waitConnected(10.0));
  Step s25 = callStep(25, &called);
  ASSERT_TRUE(called && s25.response.success);
  for (int i = 0; i < 25; ++i) world.step();
  ASSERT_TRUE(after.waitAllAt(world, s25.response.t));
  expectSameState(expectedRod(world, "rod"), after.rod("rod").back(), "rod after set_state");
  expectSameState(expectedRoller(world, "hoop"), after.roller("hoop").back(), "the spawned hoop");
  expectSameState(expectedRoller(world, "sphere"), after.roller("sphere").back(), "sphere");

  ASSERT_TRUE(commands.waitCount(4));
  const auto log = commands.received();
  ASSERT_EQ(log.size(), 4u);
  const std::vector<std::string> kinds = {"config", "spawn", "set_state", "delete"};
  for (std::size_t i = 0; i < log.size(); ++i) {
    EXPECT_EQ(log[i].header.seq, i);
    EXPECT_EQ(log[i].kind, kinds[i]);
    if (i > 0) EXPECT_EQ(log[i].step, static_cast<std::uint64_t>(count + 1));
  }
  EXPECT_EQ(log[1].yaml, toYaml(world.config().bodies.back()));
  EXPECT_EQ(spawn.response.t, log[1].t) << "the spawn's answer is not the t of its ~commands entry";
  ASSERT_TRUE(callEmpty("/sim/unpause"));
}

// While the world runs on (at wall pace, its stepping thread taking the lock between calls), every spawn
// answers the t it applied at: that of its ~commands entry, exactly.
TEST(SimNodeCommands, SpawnsAnswerTheTimeOfTheirCommand) {
  ros::NodeHandle nh;
  Commands commands(nh);
  ASSERT_TRUE(commands.waitCount(1)) << "no latched command on ~commands";  // connected from here on
  ASSERT_TRUE(callEmpty("/sim/unpause"));
  constexpr std::size_t kSpawns = 12;
  std::vector<std::pair<std::string, double>> answers;  // body, the answer's t
  for (std::size_t i = 0; i < kSpawns; ++i) {
    Spawn spawn;
    spawn.request.name = "ring" + std::to_string(i);
    spawn.request.body = "{type: roller, shape: ring, incline_angle: 0.4, x0: 0.5}";
    ASSERT_TRUE(serviceCalls().call("/sim/spawn", spawn));
    ASSERT_TRUE(spawn.response.success) << spawn.response.message;
    answers.emplace_back(spawn.request.name, spawn.response.t);
  }
  ASSERT_TRUE(commands.waitCount(1 + kSpawns)) << "not every spawn came on ~commands";
  const auto log = commands.received();
  for (const auto& answer : answers) {
    const std::string& name = answer.first;
    const auto is_spawn = [&](const rigid_body_sim::Command& c) {
      return c.kind == "spawn" && c.body == name;
    };
    const auto entry = std::find_if(log.begin() + 1, log.end(), is_spawn);
    ASSERT_NE(entry, log.end()) << name << " is not on ~commands";
    EXPECT_EQ(answer.second, entry->t)
        << name << ": answered t = " << answer.second << ", applied at step " << entry->step;
  }
}

RBS_ROSTEST_MAIN("test_node_commands")
