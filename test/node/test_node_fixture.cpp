// The test helpers another package uses (include/rigid_body_sim/testing/sim_fixture.h) on sim.launch held at
// t = 0: each helper does what it says, against the core World stepped alongside, and each failure says
// what it saw (a wait on a paused node, a refused step or reconfigure, a parameter the config leaves out).
#include "rigid_body_sim/testing/sim_fixture.h"

#include "node_test_util.h"

using namespace rigid_body_sim;
using namespace rigid_body_sim::test;

namespace {

// The failure's text holds `fragment`.
void expectFailureSaying(const ::testing::AssertionResult& result, const std::string& fragment) {
  EXPECT_FALSE(result);
  EXPECT_NE(std::string(result.message()).find(fragment), std::string::npos) << result.message();
}

}  // namespace

TEST(SimFixture, EveryHelperAndWhatItsFailuresSay) {
  const WorldConfig config = loadWorldConfigFile(configPath());
  World world(config);
  const SimFixture sim;
  const SimFixture impatient("/sim", 0.5);  // for the waits that must fail
  StateLog<RodState> rod(sim, "rod");
  StateLog<RodState> rod_impatient(impatient, "rod");
  ASSERT_TRUE(rod.waitConnected());
  ASSERT_TRUE(rod_impatient.waitConnected());

  // Parameters as the launch loaded them; a key the config leaves out is named, with where every key is.
  double gravity = 0.0;
  std::string type;
  ASSERT_TRUE(sim.param("gravity", &gravity));
  EXPECT_EQ(gravity, config.gravity);
  ASSERT_TRUE(sim.bodyParam("rod", "type", &type));
  EXPECT_EQ(type, "rod");
  std::string substeps;  // demo.yaml leaves it out: its default, in ~get_config only
  expectFailureSaying(sim.bodyParam("rod", "substeps", &substeps), "/sim/bodies/rod/substeps");
  std::string yaml;
  ASSERT_TRUE(sim.getConfig(&yaml));
  const WorldConfig running = parseWorldConfigText(yaml, "~get_config");
  EXPECT_EQ(running.bodies.size(), config.bodies.size());
  EXPECT_NE(yaml.find("substeps: auto"), std::string::npos) << yaml;

  // Held at t = 0: a wait for a later state fails on its deadline, saying where the states stopped.
  RodState state;
  expectFailureSaying(rod_impatient.waitFor(0.1, &state), "is paused");

  // Steps: the state after them is the core World's; a refused count is a failure with the node's reason.
  double t = 0.0;
  ASSERT_TRUE(sim.step(100, &t));
  for (int i = 0; i < 100; ++i) world.step();
  EXPECT_EQ(t, world.time());
  ASSERT_TRUE(rod.waitFor(t, &state));
  expectSameState(expectedRod(world, "rod"), state, "rod after 100 steps");
  expectFailureSaying(sim.step(0), "refused");

  // A key through the reconfigure server: taken, or refused saying what the server shows instead.
  ASSERT_TRUE(sim.set("rod", "k", 2000.0));
  expectFailureSaying(sim.set("rod", "k", -5.0), "it shows k = 2000");
  expectFailureSaying(sim.set("sphere", "shape", "cube"), "refused shape = cube: it shows shape = sphere");
  expectFailureSaying(sim.set("rod", "stiffness", 1.0), "no number key stiffness");
  double k = 0.0;
  ASSERT_TRUE(sim.bodyParam("rod", "k", &k));
  ASSERT_TRUE(sim.set("rod", "k", k));  // the config's again (a stiffer k sub-steps even a free fall)

  // Reset: every body from its initial conditions, time going on; unpause runs on, pause holds.
  ASSERT_TRUE(sim.reset());
  ASSERT_TRUE(sim.step(1, &t));
  World fresh(config);
  fresh.step();
  ASSERT_TRUE(rod.waitFor(t, &state));
  EXPECT_EQ(state.x, expectedRod(fresh, "rod").x);
  EXPECT_EQ(state.y, expectedRod(fresh, "rod").y);
  ASSERT_TRUE(sim.unpause());
  ASSERT_TRUE(rod.waitFor(t + 0.2, &state));
  ASSERT_TRUE(sim.pause());
}

RBS_ROSTEST_MAIN("test_node_fixture")
