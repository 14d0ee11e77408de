// The bodies' reconfigure servers (ros/reconfigure_servers.h) under rostest's master, without sim_node
// (reconfigure_servers.test): the test is the node, its world a config validated by the core World. Each
// body's server starts with the body's values (not the .cfg defaults), its first callback asks for no change,
// and a body gone before its turn gets none; a request is handed over as a change and the server shows what
// runs afterwards (a refusal snaps back); a spawn starts a server, a delete ends one, a reconfigure from
// elsewhere shows on parameter_updates.
#include <dynamic_reconfigure/Config.h>

#include "node_test_util.h"
#include "rigid_body_sim/io/config_writer.h"
#include "rigid_body_sim/ros/reconfigure_servers.h"
#include "test_util.h"

using namespace rigid_body_sim;
using namespace rigid_body_sim::test;

namespace {

constexpr double kTimeout = 20.0;  // wall seconds for any wait

// The node's side: a running config, changed only into one the core World accepts.
class FakeWorld {
 public:
  explicit FakeWorld(WorldConfig config) : config_(std::move(config)) {}

  std::optional<BodyConfig> find(const std::string& name) {
    std::lock_guard<std::mutex> lock(mutex_);
    return bodyLocked(name) ? std::optional(*bodyLocked(name)) : std::nullopt;
  }
  std::optional<BodyConfig> change(const std::string& name,
                                   const ReconfigureServers::Reconfigured& reconfigured) {
    std::lock_guard<std::mutex> lock(mutex_);
    BodyConfig* body = bodyLocked(name);
    if (!body) return std::nullopt;
    ++requests_;
    try {
      WorldConfig asked = config_;
      *std::find_if(asked.bodies.begin(), asked.bodies.end(), [&](const auto& b) { return b.name == name; }) =
          reconfigured(*body);
      const World validated(asked);
      if (toYaml(asked) != toYaml(config_)) ++changes_;
      config_ = asked;
    } catch (const ConfigError&) {
      ++refusals_;
    }
    return *bodyLocked(name);
  }
  int requests() {
    std::lock_guard<std::mutex> lock(mutex_);
    return requests_;
  }
  int changes() {
    std::lock_guard<std::mutex> lock(mutex_);
    return changes_;
  }
  int refusals() {
    std::lock_guard<std::mutex> lock(mutex_);
    return refusals_;
  }

 private:
  BodyConfig* bodyLocked(const std::string& name) {
    for (auto& body : config_.bodies)
      if (body.name == name) return &body;
    return nullptr;
  }

  std::mutex mutex_;
  WorldConfig config_;
  int requests_ = 0;
  int changes_ = 0;
  int refusals_ = 0;
};

bool waitUntil(const std::function<bool()>& holds) { return test::waitUntil(holds, kTimeout); }

bool served(const std::string& body) {
  return ros::service::exists("/sim/" + body + "/set_parameters", false);
}

double rodK(const BodyConfig& body) { return std::get<RodConfig>(body.config).params.k; }

TEST(ReconfigureServers, ServeEachBodyAndFollowTheWorld) {
  WorldConfig config = loadWorldConfigFile(test::config("demo.yaml"));
  ASSERT_EQ(config.bodies[0].name, "rod");
  std::get<RodConfig>(config.bodies[0].config).params.k = 2500.0;  // not the .cfg's default
  FakeWorld world(config);
  ReconfigureServers servers(
      ros::NodeHandle("/sim"),
      [&](const std::string& name, const ReconfigureServers::Reconfigured& reconfigured) {
        return world.change(name, reconfigured);
      },
      [&](const std::string& name) { return name == "ring" ? std::nullopt : world.find(name); });

  std::vector<std::string> names;
  for (const auto& body : config.bodies) names.push_back(body.name);
  ASSERT_EQ(names.back(), "bowler");
  servers.startAll([config] { return config; });
  // Servers start in batches, made on several threads at once: in no particular order within a batch.
  ASSERT_TRUE(waitUntil([&] {
    for (const auto& name : names)
      if (name != "ring" && !served(name)) return false;
    return true;
  })) << "every body's server";
  EXPECT_FALSE(served("ring")) << "a body the world no longer has gets none";
  // A server starts showing what runs: it asks the world for nothing, and mirrors the body's values on the
  // parameter server (as dynamic_reconfigure's own server does).
  EXPECT_EQ(world.requests(), 0) << "a server's start calls back";
  EXPECT_EQ(world.changes(), 0);
  double mirrored_k = 0.0;  // a server's values go to the parameter server before its service is up
  EXPECT_TRUE(ros::param::get("/sim/rod/k", mirrored_k));
  EXPECT_EQ(mirrored_k, 2500.0);
  std::string mirrored_shape;
  EXPECT_TRUE(ros::param::get("/sim/sphere/shape", mirrored_shape));
  EXPECT_EQ(mirrored_shape, "sphere");

  bool called = false;
  EXPECT_EQ(doubleOf(callReconfigure("rod", {}, {}, &called), "k"), 2500.0) << "the body's value";
  ASSERT_TRUE(called);
  EXPECT_EQ(doubleOf(callReconfigure("rod", {{"k", 2000.0}}, {}, &called), "k"), 2000.0);
  EXPECT_EQ(rodK(*world.find("rod")), 2000.0);
  EXPECT_EQ(world.changes(), 1);
  EXPECT_EQ(doubleOf(callReconfigure("rod", {{"k", -5.0}}, {}, &called), "k"), 2000.0)
      << "refused: snaps back";
  EXPECT_EQ(world.refusals(), 1);
  EXPECT_EQ(rodK(*world.find("rod")), 2000.0);

  // follow() belongs to the spinner thread: called here while no callback of the servers runs.
  ros::NodeHandle nh;
  std::mutex mutex;
  std::vector<double> shown_k;
  const ros::Subscriber updates = nh.subscribe<dynamic_reconfigure::Config>(
      "/sim/rod/parameter_updates", 10, [&](const dynamic_reconfigure::Config::ConstPtr& shown) {
        std::lock_guard<std::mutex> lock(mutex);
        shown_k.push_back(doubleOf(*shown, "k"));
      });
  ASSERT_TRUE(waitUntil([&] { return updates.getNumPublishers() > 0; }));
  WorldCommand stiffer;
  stiffer.kind = WorldCommand::Kind::Reconfigure;
  stiffer.body = "rod";
  stiffer.config = *world.find("rod");
  std::get<RodConfig>(stiffer.config.config).params.k = 3000.0;
  servers.follow(stiffer);
  EXPECT_TRUE(waitUntil([&] {
    std::lock_guard<std::mutex> lock(mutex);
    return !shown_k.empty() && shown_k.back() == 3000.0;
  })) << "a reconfigure made elsewhere (a drop in rviz) shows on the server";

  WorldCommand spawn;
  spawn.kind = WorldCommand::Kind::Spawn;
  spawn.body = "ball";
  spawn.config = parseBodyText("ball", "{type: roller, radius: 0.3}");
  servers.follow(spawn);
  EXPECT_TRUE(served("ball")) << "a spawned body's server starts at once";
  EXPECT_EQ(doubleOf(callReconfigure("ball", {}, {}, &called), "radius"), 0.3);

  WorldCommand remove;
  remove.kind = WorldCommand::Kind::Delete;
  remove.body = "sphere";
  servers.follow(remove);
  EXPECT_TRUE(waitUntil([] { return !served("sphere"); })) << "a deleted body's server goes";
}

TEST(ReconfigureServers, WithKeysParsesAsARequest) {
  const WorldConfig config = loadWorldConfigFile(test::config("demo.yaml"));
  const BodyConfig dropped = ReconfigureServers::withKeys(config.bodies[0], {{"x0", 1.5}, {"theta0", 0.25}});
  BodyConfig expected = config.bodies[0];
  std::get<RodConfig>(expected.config).initial.x = 1.5;
  std::get<RodConfig>(expected.config).initial.theta = 0.25;
  EXPECT_EQ(toYaml(dropped), toYaml(expected));
}

}  // namespace

// One spinner thread, as in sim_node: the servers and their callbacks belong to it.
int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_node_reconfigure_servers");
  ros::NodeHandle nh;
  ros::AsyncSpinner spinner(1);
  spinner.start();
  const int result = RUN_ALL_TESTS();
  spinner.stop();
  ros::shutdown();
  return result;
}
