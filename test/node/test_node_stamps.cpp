// Stamps are current (wall-clock stamps, the default): through sim.launch, with and without record:=true
// (where stepping waits until the recorder has subscribed: start_on_subscribers), a tf2 listener finds
// every body's transform at ros::Time::now() within a short timeout, and a state arrives within one
// publishing period (plus a margin) of its stamp. After a pause the stamps are current again, and they
// never go back.
#include <algorithm>

#include <tf2_ros/transform_listener.h>

#include "node_test_util.h"

using namespace rigid_body_sim;
using namespace rigid_body_sim::test;

namespace {

constexpr double kLookupTimeout = 0.5;  // s: a short wait for the next publication
constexpr double kMargin = 0.010;       // s beyond one publishing period for the median delay
constexpr double kLateMargin = 0.025;   // s beyond it for most states (a loaded machine wakes late)
constexpr double kEarly = 0.001;        // s: a stamp may lie this much after its arrival (clock reads)

struct Arrival {
  ros::Time stamp;
  ros::Time received;
};

// Every state's stamp and arrival time, per body.
class Arrivals {
 public:
  Arrivals(ros::NodeHandle& nh, const World& world) {
    for (const auto& body : world.bodies()) {
      const std::string topic = "/sim/" + body.name + "/state";
      auto& into = arrivals_[body.name];
      if (std::holds_alternative<Rod>(body.model)) {
        subs_.push_back(nh.subscribe<RodState>(
            topic, 1000, [this, &into](const RodState::ConstPtr& m) { add(into, m->header.stamp); }));
      } else {
        subs_.push_back(nh.subscribe<RollerState>(
            topic, 1000, [this, &into](const RollerState::ConstPtr& m) { add(into, m->header.stamp); }));
      }
    }
  }
  ~Arrivals() {
    for (auto& sub : subs_) sub.shutdown();
  }

  bool waitConnected(double timeout) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::WallTime::now() < end) {
      if (std::all_of(subs_.begin(), subs_.end(), [](const auto& s) { return s.getNumPublishers() > 0; }))
        return true;
      ros::WallDuration(0.02).sleep();
    }
    return false;
  }
  // Waits until every body has at least n arrivals.
  bool waitEach(std::size_t n, double timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    return cv_.wait_for(lock, std::chrono::duration<double>(timeout), [&] {
      for (const auto& [name, list] : arrivals_)
        if (list.size() < n) return false;
      return true;
    });
  }
  std::map<std::string, std::vector<Arrival>> take() {
    std::lock_guard<std::mutex> lock(mutex_);
    auto taken = arrivals_;
    for (auto& [name, list] : arrivals_) list.clear();
    return taken;
  }

 private:
  void add(std::vector<Arrival>& into, const ros::Time& stamp) {
    const ros::Time now = ros::Time::now();
    std::lock_guard<std::mutex> lock(mutex_);
    into.push_back({stamp, now});
    cv_.notify_all();
  }
  std::mutex mutex_;
  std::condition_variable cv_;
  std::vector<ros::Subscriber> subs_;
  std::map<std::string, std::vector<Arrival>> arrivals_;
};

// Every body's transform at now, ten times each; the delays of the states that arrived, and their order.
void expectCurrent(const WorldConfig& config, tf2_ros::Buffer& buffer,
                   const std::map<std::string, std::vector<Arrival>>& arrivals, const std::string& when) {
  SCOPED_TRACE(when);
  for (int i = 0; i < 10; ++i) {
    for (const auto& body : config.bodies) {
      std::string error;
      EXPECT_TRUE(buffer.canTransform(config.world_frame, body.name, ros::Time::now(),
                                      ros::Duration(kLookupTimeout), &error))
          << body.name << " at now: " << error;
    }
  }
  const double period = 1.0 / config.publish_rate;
  for (const auto& [name, list] : arrivals) {
    ASSERT_GE(list.size(), 20u) << name;
    std::vector<double> delays;
    for (std::size_t j = 0; j < list.size(); ++j) {
      delays.push_back((list[j].received - list[j].stamp).toSec());
      if (j > 0) EXPECT_GT(list[j].stamp, list[j - 1].stamp) << name << ": stamps not increasing";
    }
    std::sort(delays.begin(), delays.end());
    const double median = delays[delays.size() / 2];
    const auto within =
        std::count_if(delays.begin(), delays.end(), [&](double d) { return d <= period + kLateMargin; });
    EXPECT_GE(delays.front(), -kEarly) << name << ": a stamp after its arrival";
    EXPECT_LE(median, period + kMargin) << name << ": states arrive late for their stamps (median delay)";
    EXPECT_GE(static_cast<double>(within), 0.8 * static_cast<double>(delays.size()))
        << name << ": fewer than 80 % of the states arrive within " << period + kLateMargin
        << " s of their stamp; the slowest took " << delays.back() << " s";
  }
}

}  // namespace

TEST(SimNodeStamps, CurrentForListenersOnWallTime) {
  ros::NodeHandle nh;
  const WorldConfig config = loadWorldConfigFile(configPath());
  const World world(config);
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  Arrivals arrivals(nh, world);
  ASSERT_TRUE(arrivals.waitConnected(30.0)) << "the node does not publish every state to this test";
  const auto per_second = static_cast<std::size_t>(config.publish_rate);
  ASSERT_TRUE(arrivals.waitEach(1, 30.0)) << "no state of some body";
  arrivals.take();  // from the first state on: stepping has started
  ASSERT_TRUE(arrivals.waitEach(3 * per_second, 30.0)) << "not 3 s of states";
  const auto running = arrivals.take();
  expectCurrent(config, buffer, running, "running");

  // Paused for a while, then on: the stamps are current again, and later than every one before.
  ASSERT_TRUE(callEmpty("/sim/pause"));
  ros::WallDuration(1.5).sleep();  // the pause the scenario is about
  arrivals.take();
  ASSERT_TRUE(callEmpty("/sim/unpause"));
  ASSERT_TRUE(arrivals.waitEach(3 * per_second, 30.0)) << "not 3 s of states after the pause";
  const auto resumed = arrivals.take();
  expectCurrent(config, buffer, resumed, "after a pause of 1.5 s");
  for (const auto& [name, list] : resumed) {
    EXPECT_GT(list.front().stamp, running.at(name).back().stamp) << name << ": a stamp went back";
  }
}

RBS_ROSTEST_MAIN("test_node_stamps")
