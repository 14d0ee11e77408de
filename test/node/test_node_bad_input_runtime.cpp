// sim_node at run time on bad input: a table of reconfigure requests (values out of the core's ranges, which
// the servers pass on unclamped: the .cfg has no ranges; 0 where > 0 is needed, NaN, relations between
// keys, names outside an enum), `rosparam set` + `dynparam set_from_parameters`, ~step with absurd counts,
// and ~spawn of a name that is no ASCII. Each one must be refused with exactly one line on /rosout at WARN
// (the caller's mistake, which the caller is told), naming the value asked for; the server must keep
// showing the values in use, the node must stay alive, and afterwards the states must equal the core
// World's, as if nothing had been asked.
#include <cstdlib>

#include <dynamic_reconfigure/Reconfigure.h>

#include "node_test_util.h"
#include "rigid_body_sim/Spawn.h"
#include "rigid_body_sim/core/constants.h"
#include "test_util.h"

using namespace rigid_body_sim;
using namespace rigid_body_sim::test;

namespace {

const double kNan = std::numeric_limits<double>::quiet_NaN();

struct BadRequest {
  std::string what;
  std::string body;
  std::vector<std::pair<std::string, double>> doubles;
  std::vector<std::pair<std::string, std::string>> strings;
  std::string named = "";  // a fragment the refusal must hold (the value asked for)
};

const std::vector<BadRequest>& badRequests() {
  static const std::vector<BadRequest> rows = {
      {"rod k = -5 (not clamped to a bound)", "rod", {{"k", -5.0}}, {}, "'k': value -5 is not allowed"},
      {"rod k = -1e300", "rod", {{"k", -1e300}}, {}, "value -1e+300 is not"},
      {"rod floor_length = -1", "rod", {{"floor_length", -1.0}}, {}, "'floor_length': value -1 is not"},
      {"rod x0 off its bounded floor",
       "rod",
       {{"x0", 11.0}},
       {},
       "value 11 is not allowed (allowed: a position on the floor"},
      {"rod floor_length below x0", "rod", {{"x0", 8.0}, {"floor_length", 6.0}}, {}, "floor_length = 6"},
      {"sphere mu_s = -1 (not clamped to 0)", "sphere", {{"mu_s", -1.0}}, {}, "'mu_s': value -1 is not"},
      {"sphere incline_angle = 4", "sphere", {{"incline_angle", 4.0}}, {}, "value 4 is not"},
      {"rod k = 0", "rod", {{"k", 0.0}}, {}},
      {"rod mass = 0", "rod", {{"mass", 0.0}}, {}},
      {"rod length = 0", "rod", {{"length", 0.0}}, {}},
      {"rod k = NaN", "rod", {{"k", kNan}}, {}},
      {"rod y0 = NaN", "rod", {{"y0", kNan}}, {}},
      {"rod stiff k for a light rod", "rod", {{"k", 1e12}, {"mass", 1e-9}}, {}},
      {"rod integrator leapfrog", "rod", {}, {{"integrator", "leapfrog"}}},
      {"rod substeps 0", "rod", {}, {{"substeps", "0"}}},
      {"rod substeps 1 where it is unstable", "rod", {{"k", 1e6}}, {{"substeps", "1"}}},  // omega_c dt = 2.83
      {"sphere mu_d > mu_s", "sphere", {{"mu_d", 0.9}}, {}},
      {"sphere mu_s below mu_d", "sphere", {{"mu_s", 0.1}}, {}},
      {"sphere x0 beyond incline_length", "sphere", {{"x0", 6.0}}, {}},
      {"bowler incline_length below x0", "bowler", {{"x0", 10.0}, {"incline_length", 8.0}}, {}},
      {"sphere vertical slope", "sphere", {{"incline_angle", kPi / 2}}, {}},
      {"sphere incline_angle NaN", "sphere", {{"incline_angle", kNan}}, {}},
      {"sphere radius = 0", "sphere", {{"radius", 0.0}}, {}},
      {"sphere mass = 0", "sphere", {{"mass", 0.0}}, {}},
      {"sphere factor contradicting shape", "sphere", {{"inertia_factor", 0.3}}, {}},
      {"sphere shape cube", "sphere", {}, {{"shape", "cube"}}},
      {"sphere custom with factor 0", "sphere", {{"inertia_factor", 0.0}}, {{"shape", "custom"}}},
      {"bowler x0 beyond the slope", "bowler", {{"x0", 20.0}}, {}},
      {"rod moment of inertia underflows to 0",
       "rod",
       {{"mass", 1e-160}, {"length", 1e-160}, {"k", 1e-150}},
       {},
       "moment of inertia M L^2 / 12 = 0 is not allowed"},
      {"sphere c M R underflows", "sphere", {{"mass", 1e-160}, {"radius", 1e-160}}, {}, "c M R = 4e-321"},
  };
  return rows;
}

// The node's lines at WARN and above since the last take(), each with its level in front ("WARN: ...").
// A refused ~step of a count no test row uses is logged after whatever the requests before it caused, and
// /rosout keeps the node's order: the lines before that one are exactly those of the requests, with no
// window to wait out for a late extra line.
class WarnLog {
 public:
  explicit WarnLog(ros::NodeHandle& nh) : log_(nh) {}
  bool waitConnected(double timeout) { return log_.waitConnected(timeout); }
  std::vector<std::string> take() {
    bool called = false;
    const Step marker = callStep(kMarkerSteps, &called);
    EXPECT_TRUE(called && !marker.response.success) << "the marker step was not refused";
    const auto lines = log_.takeUntil("steps " + std::to_string(kMarkerSteps) + " ", 30.0);
    EXPECT_TRUE(lines.has_value()) << "the marker line never came";
    std::vector<std::string> texts;
    for (const auto& line : lines.value_or(std::vector<rosgraph_msgs::Log>{})) {
      if (line.level < rosgraph_msgs::Log::WARN) continue;
      texts.push_back((line.level == rosgraph_msgs::Log::WARN ? "WARN: " : "ERROR or worse: ") + line.msg);
    }
    return texts;
  }

 private:
  static constexpr std::uint32_t kMarkerSteps = 4000000000u;  // beyond 600 s of steps: refused
  NodeLog log_;
};

dynamic_reconfigure::Config reconfigure(const BadRequest& row, bool* called) {
  return callReconfigure(row.body, row.doubles, row.strings, called);
}

// The values a server shows, exactly (NaN never equals, so a NaN shown fails too).
void expectSameConfig(const dynamic_reconfigure::Config& expected, const dynamic_reconfigure::Config& got) {
  ASSERT_EQ(expected.doubles.size(), got.doubles.size());
  for (std::size_t i = 0; i < expected.doubles.size(); ++i) {
    EXPECT_EQ(expected.doubles[i].name, got.doubles[i].name);
    EXPECT_EQ(expected.doubles[i].value, got.doubles[i].value) << got.doubles[i].name;
  }
  ASSERT_EQ(expected.strs.size(), got.strs.size());
  for (std::size_t i = 0; i < expected.strs.size(); ++i) {
    EXPECT_EQ(expected.strs[i].value, got.strs[i].value) << got.strs[i].name;
  }
}

void expectOneWarningNaming(const std::vector<std::string>& lines, const std::string& body,
                            const std::string& named = "") {
  ASSERT_EQ(lines.size(), 1u) << "lines: " << ::testing::PrintToString(lines);
  EXPECT_EQ(lines[0].rfind("WARN: ", 0), 0u) << lines[0];
  EXPECT_NE(lines[0].find("body '" + body + "'"), std::string::npos) << lines[0];
  EXPECT_NE(lines[0].find("is not allowed (allowed: "), std::string::npos) << lines[0];
  EXPECT_NE(lines[0].find(named), std::string::npos) << lines[0];
}

}  // namespace

TEST(SimNodeBadInputRuntime, TheDocsCountTheRequestsThereAre) {
  const std::string docs = slurp(fs::path(RBS_README).parent_path() / "docs" / "reliability.md");
  const std::string count =
      "`bad_input_runtime.test` | " + std::to_string(badRequests().size()) + " reconfigure";
  EXPECT_NE(docs.find(count), std::string::npos) << "docs/reliability.md should say " << count;
}

TEST(SimNodeBadInputRuntime, RefusedOnceLoggedNothingChangedNodeAlive) {
  ros::NodeHandle nh;
  const WorldConfig config = loadWorldConfigFile(configPath());
  World world(config);
  StateCollector c(nh, world);
  WarnLog errors(nh);
  ASSERT_TRUE(c.waitConnected(10.0));
  ASSERT_TRUE(errors.waitConnected(10.0));
  ASSERT_TRUE(ros::service::waitForService("/sim/step", 10000));
  for (const char* body : {"rod", "sphere", "bowler"}) {
    ASSERT_TRUE(ros::service::waitForService(std::string("/sim/") + body + "/set_parameters", 10000));
  }
  ASSERT_TRUE(callEmpty("/sim/pause"));
  bool called = false;
  const Step sync = callStep(1, &called);
  ASSERT_TRUE(called && sync.response.success) << sync.response.message;
  for (std::int64_t i = stepIndex(sync.response.t, config.rate); i > 0; --i) world.step();
  errors.take();

  // The values each server shows before anything is asked (an empty request changes nothing).
  std::map<std::string, dynamic_reconfigure::Config> shown;
  for (const char* body : {"rod", "sphere", "bowler"}) {
    shown[body] = reconfigure({"", body, {}, {}}, &called);
    ASSERT_TRUE(called);
  }
  ASSERT_TRUE(errors.take().empty()) << "an empty request was refused";

  // --- dynamic_reconfigure requests
  for (const BadRequest& row : badRequests()) {
    SCOPED_TRACE(row.what);
    const auto returned = reconfigure(row, &called);
    ASSERT_TRUE(called) << "the node no longer answers";
    expectSameConfig(shown[row.body], returned);
    expectOneWarningNaming(errors.take(), row.body, row.named);
  }

  // --- the command line: `dynparam set NODE KEY VALUE`, and parameter values pushed with
  // `dynparam set_from_parameters NODE _key:=value` (its way of copying parameters into a running server)
  struct CommandLine {
    std::string body, verb, arguments, named;
  };
  for (const CommandLine& row :
       {CommandLine{"rod", "set", "k -5", "'k': value -5 is not allowed"},
        CommandLine{"sphere", "set_from_parameters", "_mu_d:=0.9", "value 0.9"},
        CommandLine{"rod", "set_from_parameters", "_mass:=0.0", "'mass': value 0"}}) {
    const std::string& body = row.body;
    SCOPED_TRACE(body + " " + row.verb + " " + row.arguments);
    const std::string command = "rosrun dynamic_reconfigure dynparam " + row.verb + " /sim/" + body + " " +
                                row.arguments + " __name:=bad_input_dynparam_" + body + " >/dev/null";
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    expectOneWarningNaming(errors.take(), body, row.named);
    const auto returned = reconfigure({"", body, {}, {}}, &called);
    ASSERT_TRUE(called);
    expectSameConfig(shown[body], returned);
  }
  // `rosparam set` on a server's parameter changes nothing by itself; the next reconfigure writes back
  // the values in use.
  {
    ros::param::set("/sim/sphere/mu_d", 0.9);
    const auto returned = reconfigure({"", "sphere", {{"mu_s", 0.2}}, {}}, &called);
    ASSERT_TRUE(called);
    expectSameConfig(shown["sphere"], returned);
    double mu_d = 0.0;
    ASSERT_TRUE(ros::param::get("/sim/sphere/mu_d", mu_d));
    EXPECT_EQ(mu_d, 0.15);
    EXPECT_TRUE(errors.take().empty());
  }

  // --- ~step with absurd counts, and while running
  for (const std::uint32_t steps : {0u, 600001u, 4294967295u}) {
    SCOPED_TRACE("step " + std::to_string(steps));
    const Step s = callStep(steps, &called);
    ASSERT_TRUE(called) << "the node no longer answers";
    EXPECT_FALSE(s.response.success);
    EXPECT_EQ(s.response.t, world.time()) << "a refused step moved the time";
    const auto lines = errors.take();
    ASSERT_EQ(lines.size(), 1u) << ::testing::PrintToString(lines);
    EXPECT_EQ(lines[0].rfind("WARN: ", 0), 0u) << lines[0];
    EXPECT_NE(lines[0].find(std::to_string(steps)), std::string::npos) << lines[0];
  }

  // --- a body name that is no ASCII: refused, and named as written in the answer and on /rosout
  {
    const std::string name = "\xc3\xbcn\xc3\xaf";  // "ünï" in UTF-8
    Spawn spawn;
    spawn.request.name = name;
    spawn.request.body = "{type: rod}";
    ASSERT_TRUE(serviceCalls().call("/sim/spawn", spawn)) << "the node no longer answers";
    EXPECT_FALSE(spawn.response.success);
    EXPECT_NE(spawn.response.message.find("'" + name + "'"), std::string::npos) << spawn.response.message;
    const auto lines = errors.take();
    ASSERT_EQ(lines.size(), 1u) << ::testing::PrintToString(lines);
    EXPECT_NE(lines[0].find("'" + name + "'"), std::string::npos) << lines[0];
    EXPECT_EQ(lines[0].find('?'), std::string::npos) << lines[0];
  }

  // --- nothing changed: 500 steps later every body is where the core World, never reconfigured, is
  c.clear();
  const Step s = callStep(500, &called);
  ASSERT_TRUE(called && s.response.success) << s.response.message;
  for (int i = 0; i < 500; ++i) world.step();
  ASSERT_EQ(s.response.t, world.time());
  ASSERT_TRUE(c.waitAllAt(world, world.time(), 5.0)) << "no state of every body at t = " << world.time();
  for (const auto& body : world.bodies()) {
    if (std::holds_alternative<Rod>(body.model)) {
      expectSameState(expectedRod(world, body.name), c.rod(body.name).back(), body.name);
    } else {
      expectSameState(expectedRoller(world, body.name), c.roller(body.name).back(), body.name);
    }
  }
  EXPECT_TRUE(errors.take().empty());
}

RBS_ROSTEST_MAIN("test_node_bad_input_runtime")
