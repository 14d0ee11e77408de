// sim_node's dynamic_reconfigure servers: accepted changes apply exactly as in the core World, refused
// ones leave everything unchanged and the server shows the old values, new initial conditions restart, a
// rod's bounded floor restarts it as in the core, and the README's `dynparam set_from_parameters` example
// works as written.
#include <cstdlib>
#include <sstream>

#include "node_test_util.h"
#include "test_util.h"

using namespace rigid_body_sim;
using namespace rigid_body_sim::test;

namespace {

dynamic_reconfigure::Config setDouble(const std::string& body, const std::string& key, double value,
                                      bool* called) {
  return callReconfigure(body, {{key, value}}, {}, called);
}

// Sets one number of a body, which the server must accept and show.
void setAccepted(const std::string& body, const std::string& key, double value) {
  bool called = false;
  const auto shown = setDouble(body, key, value, &called);
  ASSERT_TRUE(called) << body << "." << key;
  EXPECT_EQ(value, doubleOf(shown, key)) << body << "." << key;
}

Rod& rodOf(World& w, const std::string& name) { return std::get<Rod>(w.find(name)->model); }
Roller& rollerOf(World& w, const std::string& name) { return std::get<Roller>(w.find(name)->model); }

// Steps the node by n and `world` along; every state the node publishes during the steps (each publishing
// instant, and the end) must equal `world` at that step, exactly.
void stepAndCompare(StateCollector& c, World& world, std::uint32_t n, const std::string& what) {
  c.clear();
  bool called = false;
  Step s = callStep(n, &called);
  ASSERT_TRUE(called) << what;
  ASSERT_TRUE(s.response.success) << what << ": " << s.response.message;
  std::map<double, std::map<std::string, RodState>> rods;
  std::map<double, std::map<std::string, RollerState>> rollers;
  for (std::uint32_t i = 0; i < n; ++i) {
    world.step();
    for (const auto& body : world.bodies()) {
      if (std::holds_alternative<Rod>(body.model)) {
        rods[world.time()][body.name] = expectedRod(world, body.name);
      } else {
        rollers[world.time()][body.name] = expectedRoller(world, body.name);
      }
    }
  }
  ASSERT_EQ(world.time(), s.response.t) << what;
  const double end = s.response.t;
  ASSERT_TRUE(c.waitFor(
      [&] {
        for (const auto& [name, msgs] : c.rodsLocked())
          if (msgs.empty() || msgs.back().t != end) return false;
        for (const auto& [name, msgs] : c.rollersLocked())
          if (msgs.empty() || msgs.back().t != end) return false;
        return c.rodsLocked().size() + c.rollersLocked().size() == world.bodies().size();
      },
      5.0))
      << what << ": no state at t = " << end << " for some body";
  std::size_t compared = 0;
  for (const auto& body : world.bodies()) {
    if (std::holds_alternative<Rod>(body.model)) {
      for (const auto& msg : c.rod(body.name)) {
        ASSERT_TRUE(rods.count(msg.t)) << what << " " << body.name << ": unexpected t " << msg.t;
        expectSameState(rods[msg.t][body.name], msg, what + " " + body.name);
        ++compared;
      }
    } else {
      for (const auto& msg : c.roller(body.name)) {
        ASSERT_TRUE(rollers.count(msg.t)) << what << " " << body.name << ": unexpected t " << msg.t;
        expectSameState(rollers[msg.t][body.name], msg, what + " " + body.name);
        ++compared;
      }
    }
    if (::testing::Test::HasFailure()) return;
  }
  EXPECT_GE(compared, world.bodies().size());
}

// The README's command line that runs `dynparam set_from_parameters`, as written (its comment left out).
std::string readmeSetFromParameters() {
  for (const std::string& line : test::lines(test::slurp(RBS_README))) {
    const auto start = line.find("rosrun dynamic_reconfigure dynparam set_from_parameters");
    if (start != std::string::npos) return line.substr(start, line.find('#') - start);
  }
  return "";
}

// The `_key:=value` assignments of a command line.
std::vector<std::pair<std::string, double>> assignments(const std::string& command) {
  std::vector<std::pair<std::string, double>> found;
  std::istringstream words(command);
  for (std::string word; words >> word;) {
    const auto equals = word.find(":=");
    if (word[0] == '_' && word[1] != '_' && equals != std::string::npos) {
      found.emplace_back(word.substr(1, equals - 1), std::stod(word.substr(equals + 2)));
    }
  }
  return found;
}

}  // namespace

TEST(SimNodeReconfigure, ChangesApplyLikeTheCore) {
  ros::NodeHandle nh;
  const WorldConfig config = loadWorldConfigFile(configPath());
  World world(config);

  StateCollector c(nh, world);
  ASSERT_TRUE(c.waitConnected(10.0));
  ASSERT_TRUE(ros::service::waitForService("/sim/step", 10000));
  ASSERT_TRUE(ros::service::waitForService("/sim/rod/set_parameters", 10000));
  ASSERT_TRUE(ros::service::waitForService("/sim/sphere/set_parameters", 10000));
  ASSERT_TRUE(ros::service::waitForService("/sim/cylinder/set_parameters", 10000));
  ASSERT_TRUE(callEmpty("/sim/pause"));

  // Bring the local World to the node's step count: step(1) tells the time. Its states come after every
  // state published before the pause (each topic delivers in order).
  bool called = false;
  Step s = callStep(1, &called);
  ASSERT_TRUE(called);
  ASSERT_TRUE(s.response.success) << s.response.message;
  const std::int64_t n0 = stepIndex(s.response.t, config.rate);
  for (std::int64_t i = 0; i < n0; ++i) world.step();
  ASSERT_TRUE(c.waitAllAt(world, s.response.t)) << "no state of every body after step(1)";
  stepAndCompare(c, world, 1, "before any change");

  // --- accepted: rod k = 2000, sphere mu_s = 0.16 (below what rolling on this slope needs)
  const World unchanged_before = world;
  setAccepted("rod", "k", 2000.0);
  RodParams rod_params = rodOf(world, "rod").params();
  rod_params.k = 2000.0;
  rodOf(world, "rod").setParams(rod_params);

  setAccepted("sphere", "mu_s", 0.16);
  RollerParams sphere_params = rollerOf(world, "sphere").params();
  sphere_params.mu_s = 0.16;
  rollerOf(world, "sphere").setParams(sphere_params);

  // The cylinder slips on its slope; at 0.3 rad its slip decays and it rolls (tan 0.3 < mu_s (1 + c) / c).
  setAccepted("cylinder", "incline_angle", 0.3);
  RollerParams cylinder_params = rollerOf(world, "cylinder").params();
  cylinder_params.incline_angle = 0.3;
  rollerOf(world, "cylinder").setParams(cylinder_params);

  // 2 s of simulated time: the rod reaches the floor, the sphere slips, the cylinder comes to roll.
  stepAndCompare(c, world, 2000, "after k = 2000, mu_s = 0.16, incline_angle = 0.3");
  EXPECT_EQ(RollMode::Rolling, rollerOf(world, "cylinder").mode());
  // The changes mattered (otherwise the comparison above would prove nothing).
  {
    World unchanged = unchanged_before;
    for (int i = 0; i < 2000; ++i) unchanged.step();
    EXPECT_NE(rodOf(unchanged, "rod").state().y, rodOf(world, "rod").state().y) << "k made no difference";
    EXPECT_NE(rollerOf(unchanged, "sphere").state().omega, rollerOf(world, "sphere").state().omega)
        << "mu_s made no difference";
    EXPECT_NE(rollerOf(unchanged, "cylinder").state().v, rollerOf(world, "cylinder").state().v)
        << "incline_angle made no difference";
  }

  // --- refused: k = 0 and mu_d > mu_s; the server shows the values in use, nothing changes
  auto rod_cfg = setDouble("rod", "k", 0.0, &called);
  ASSERT_TRUE(called) << "the node died on k = 0";
  EXPECT_EQ(2000.0, doubleOf(rod_cfg, "k"));
  const auto sphere_cfg = setDouble("sphere", "mu_d", 0.9, &called);
  ASSERT_TRUE(called) << "the node died on mu_d > mu_s";
  EXPECT_EQ(rollerOf(world, "sphere").params().mu_d, doubleOf(sphere_cfg, "mu_d"));
  EXPECT_EQ(0.16, doubleOf(sphere_cfg, "mu_s"));
  stepAndCompare(c, world, 500, "after refused k = 0, mu_d = 0.9");

  // --- new initial condition: rod y0 = 3 restarts the rod from it
  rod_cfg = setDouble("rod", "y0", 3.0, &called);
  ASSERT_TRUE(called);
  EXPECT_EQ(3.0, doubleOf(rod_cfg, "y0"));
  EXPECT_EQ(2000.0, doubleOf(rod_cfg, "k"));
  RodMotion initial = rodOf(world, "rod").initial();
  initial.y = 3.0;
  rodOf(world, "rod").setInitial(initial);
  stepAndCompare(c, world, 1, "one step after y0 = 3");
  const auto rods = c.rod("rod");
  ASSERT_FALSE(rods.empty());
  EXPECT_NEAR(3.0, rods.back().y, 1e-3);
  stepAndCompare(c, world, 300, "300 steps after y0 = 3");

  // --- a bounded floor: pushed at 2 m/s from its x0, the rod runs off a floor that ends 0.6 m further and
  // restarts, as in the core
  setAccepted("rod", "vx0", 2.0);
  initial.vx = 2.0;
  rodOf(world, "rod").setInitial(initial);
  stepAndCompare(c, world, 1, "one step after vx0 = 2");
  world.takeEvents();
  const double floor_end = initial.x + 0.6;
  setAccepted("rod", "floor_length", floor_end);
  RodParams bounded = rodOf(world, "rod").params();
  bounded.floor_length = floor_end;
  rodOf(world, "rod").setParams(bounded);
  stepAndCompare(c, world, 1500, "after floor_length = x0 + 0.6");
  int restarts = 0;
  for (const auto& event : world.takeEvents()) restarts += event.body == "rod" && event.kind == "restarted";
  EXPECT_GE(restarts, 2) << "the rod did not run off its floor";

  // --- the README's example, as written: every key it assigns applies
  const std::string command = readmeSetFromParameters();
  ASSERT_FALSE(command.empty()) << "no dynparam set_from_parameters line in the README";
  ASSERT_EQ(std::system((command + " >/dev/null 2>&1").c_str()), 0) << command;
  const std::string body = "sphere";
  ASSERT_NE(command.find("/sim/" + body + " "), std::string::npos) << command;
  const auto shown = callReconfigure(body, {}, {}, &called);
  ASSERT_TRUE(called);
  Roller& roller = rollerOf(world, body);
  RollerConfig wanted{roller.params(), roller.initial()};
  ASSERT_FALSE(assignments(command).empty()) << command;
  for (const auto& [key, value] : assignments(command)) {
    EXPECT_EQ(value, doubleOf(shown, key)) << command;
    const auto* numeric = findKey(bodyType<RollerConfig>().keys, key);
    ASSERT_TRUE(numeric && numeric->isNumber()) << key;
    numeric->field(wanted) = value;
  }
  roller.setParams(wanted.params);  // the README changes parameters only, no initial condition
  stepAndCompare(c, world, 500, "after the README's dynparam set_from_parameters");
}

RBS_ROSTEST_MAIN("test_node_reconfigure")
