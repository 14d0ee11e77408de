// sim_node at run time on bad input: a table of reconfigure requests (values out of the core's ranges, which
// the servers pass on unclamped: the .cfg has no ranges; 0 where > 0 is needed, NaN, relations between
// keys, names outside an enum), `rosparam set` + `dynparam set_from_parameters`, and ~step with absurd
// counts. Each one must be refused with exactly one line on /rosout at WARN (the caller's mistake, which
// the caller is told), naming the value asked for; the server must keep showing the values in use, the
// node must stay alive, and afterwards the states must equal the core World's, as if nothing had been
// asked.
#include <cstdlib>

#include <dynamic_reconfigure/Reconfigure.h>
#include <rosgraph_msgs/Log.h>

#include "node_test_util.h"
#include "rigid_body_sim/core/constants.h"

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
  };
  return rows;
}

// The node's lines on /rosout at WARN and above, each with its level in front ("WARN: ...").
class WarnLog {
 public:
  explicit WarnLog(ros::NodeHandle& nh)
      : sub_(nh.subscribe<rosgraph_msgs::Log>(
            "/rosout", 1000, [this](const rosgraph_msgs::Log::ConstPtr& msg) {
              if (msg->name != "/sim" || msg->level < rosgraph_msgs::Log::WARN) return;
              std::lock_guard<std::mutex> lock(mutex_);
              lines_.push_back((msg->level == rosgraph_msgs::Log::WARN ? "WARN: " : "ERROR or worse: ") +
                               msg->msg);
              arrived_.notify_all();
            })) {}
  bool waitConnected(double timeout) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
    while (sub_.getNumPublishers() == 0 && ros::WallTime::now() < end) ros::WallDuration(0.02).sleep();
    return sub_.getNumPublishers() > 0;
  }
  // The lines that arrived since the last call: waits up to 10 s for the first of `expected` (a loaded
  // machine may be slow to deliver it), then 0.3 s more for any extra line.
  std::vector<std::string> take(std::size_t expected = 1) {
    std::unique_lock<std::mutex> lock(mutex_);
    if (expected > 0)
      arrived_.wait_for(lock, std::chrono::seconds(10), [&] { return lines_.size() >= expected; });
    lock.unlock();
    ros::WallDuration(0.3).sleep();
    lock.lock();
    std::vector<std::string> taken;
    taken.swap(lines_);
    return taken;
  }

 private:
  std::mutex mutex_;
  std::condition_variable arrived_;
  std::vector<std::string> lines_;
  ros::Subscriber sub_;
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
  ros::WallDuration(0.3).sleep();
  bool called = false;
  const Step sync = callStep(1, &called);
  ASSERT_TRUE(called && sync.response.success) << sync.response.message;
  for (std::int64_t i = stepIndex(sync.response.t, config.rate); i > 0; --i) world.step();
  errors.take(0);

  // The values each server shows before anything is asked (an empty request changes nothing).
  std::map<std::string, dynamic_reconfigure::Config> shown;
  for (const char* body : {"rod", "sphere", "bowler"}) {
    shown[body] = reconfigure({"", body, {}, {}}, &called);
    ASSERT_TRUE(called);
  }
  ASSERT_TRUE(errors.take(0).empty()) << "an empty request was refused";

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
    EXPECT_TRUE(errors.take(0).empty());
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
  EXPECT_TRUE(errors.take(0).empty());
}

RBS_ROSTEST_MAIN("test_node_bad_input_runtime")
