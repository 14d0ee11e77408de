// sim_node's NaN guard, through valid input: the body `tiny` of test/faults/guard.yaml goes non-finite in
// its first step. It must be held at its initial state, one ERROR naming it and its parameters must be
// logged, no state, TF or marker may carry a non-finite number, and the other bodies must be the core
// World's prediction at every sample, as if `tiny` were not there.
#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/MarkerArray.h>

#include "node_test_util.h"

using namespace rigid_body_sim;
using namespace rigid_body_sim::test;

namespace {

bool finite(const geometry_msgs::Point& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}
bool finite(const geometry_msgs::Quaternion& q) {
  return std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z) && std::isfinite(q.w);
}
bool finite(const geometry_msgs::Vector3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Everything that /tf and /sim/markers carried, counted as it arrives.
struct Watch {
  std::mutex mutex;
  std::size_t tf = 0, tf_bad = 0, markers = 0, markers_bad = 0;

  void onTf(const tf2_msgs::TFMessage::ConstPtr& msg) {
    std::lock_guard<std::mutex> lock(mutex);
    ++tf;
    for (const auto& t : msg->transforms) {
      if (!finite(t.transform.translation) || !finite(t.transform.rotation)) ++tf_bad;
    }
  }
  void onMarkers(const visualization_msgs::MarkerArray::ConstPtr& msg) {
    std::lock_guard<std::mutex> lock(mutex);
    ++markers;
    for (const auto& m : msg->markers) {
      bool ok = finite(m.pose.position) && finite(m.pose.orientation) && finite(m.scale);
      for (const auto& p : m.points) ok = ok && finite(p);
      if (!ok) ++markers_bad;
    }
  }
};

bool finiteRod(const RodState& m) {
  for (double v : {m.t, m.x, m.y, m.theta, m.vx, m.vy, m.omega, m.energy}) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

}  // namespace

TEST(SimNodeGuard, HoldsTheNonFiniteBodyAndPublishesNothingNonFinite) {
  ros::NodeHandle nh;
  // guard.yaml must validate (test_finite_guard checks that it does and goes non-finite).
  const WorldConfig config = loadWorldConfigFile(configPath());
  // The reference: the same world without `tiny`, whose bodies are independent of it.
  WorldConfig others = config;
  others.bodies.erase(others.bodies.begin());
  ASSERT_EQ("tiny", config.bodies.front().name);
  World reference(others);
  World full(config);

  Watch watch;
  auto tf_sub = nh.subscribe<tf2_msgs::TFMessage>("/tf", 10000, &Watch::onTf, &watch);
  auto marker_sub =
      nh.subscribe<visualization_msgs::MarkerArray>("/sim/markers", 10000, &Watch::onMarkers, &watch);
  NodeLog log(nh);
  StateCollector collector(nh, full);
  ASSERT_TRUE(collector.waitConnected(10.0)) << "no publisher of the state topics";
  ASSERT_TRUE(log.waitConnected(10.0)) << "no /rosout of the node";
  double duration = 0.0;
  ros::param::get("~duration", duration);
  // The run is over when every body's state at t = duration has come, and the node's line saying so on
  // /rosout: every line it logged before has come then too.
  ASSERT_TRUE(collector.waitAllAt(full, duration, 45.0)) << "no state of every body at t = " << duration;
  const auto lines = log.takeUntil("the requested duration", 10.0);
  ASSERT_TRUE(lines.has_value()) << "the node did not say that its run ended";
  const std::vector<std::string> errors = textsAtLeast(*lines, rosgraph_msgs::Log::ERROR);

  const std::vector<RodState> tiny = collector.rod("tiny");
  ASSERT_FALSE(tiny.empty());
  EXPECT_EQ(0.0, tiny.front().t) << "stepping began before the test subscribed";
  EXPECT_EQ(duration, tiny.back().t) << "the held body's messages stopped";
  const RodMotion start = std::get<RodConfig>(config.bodies.front().config).initial;
  for (const auto& m : tiny) {
    ASSERT_TRUE(finiteRod(m)) << "non-finite state of tiny at t = " << m.t;
    // Held at its initial state: the first step already went non-finite.
    EXPECT_EQ(start.x, m.x);
    EXPECT_EQ(start.y, m.y);
    EXPECT_EQ(start.theta, m.theta);
    EXPECT_EQ(start.vx, m.vx);
    EXPECT_EQ(start.omega, m.omega);
  }

  // The others: the core World's prediction at every sample received.
  const double rate = config.rate;
  std::size_t compared = 0;
  for (const auto& body : reference.bodies()) {
    World world(others);
    if (std::holds_alternative<Rod>(body.model)) {
      for (const auto& m : collector.rod(body.name)) {
        while (world.stepCount() < stepIndex(m.t, rate)) world.step();
        expectSameState(expectedRod(world, body.name), m, body.name + " at t = " + std::to_string(m.t));
        ++compared;
      }
    } else {
      for (const auto& m : collector.roller(body.name)) {
        while (world.stepCount() < stepIndex(m.t, rate)) world.step();
        expectSameState(expectedRoller(world, body.name), m, body.name + " at t = " + std::to_string(m.t));
        ++compared;
      }
    }
  }
  EXPECT_GE(compared, tiny.size()) << "too few states of the other bodies";

  std::lock_guard<std::mutex> lock(watch.mutex);
  EXPECT_GT(watch.tf, 0u);
  EXPECT_EQ(0u, watch.tf_bad) << "non-finite transforms on /tf";
  EXPECT_GT(watch.markers, 0u);
  EXPECT_EQ(0u, watch.markers_bad) << "non-finite markers";
  ASSERT_EQ(1u, errors.size()) << "exactly one error from the node: " << ::testing::PrintToString(errors);
  const std::string& error = errors.front();
  for (const char* part :
       {"body 'tiny'", "theta became non-finite", "paused", "mass=1e-200", "length=1e-100", "k=1e-200"}) {
    EXPECT_NE(std::string::npos, error.find(part)) << part << " in: " << error;
  }
}

RBS_ROSTEST_MAIN("test_node_guard")
