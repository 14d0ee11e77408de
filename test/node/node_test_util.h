// Helpers shared by the rostest gtest nodes that drive sim_node: a collector of state messages, service
// calls, and exact comparison of a published state with the core World's prediction.
#pragma once

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <functional>
#include <limits>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <dynamic_reconfigure/Reconfigure.h>
#include <gtest/gtest.h>
#include <ros/callback_queue.h>
#include <ros/network.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Log.h>
#include <std_srvs/Empty.h>
#include <xmlrpcpp/XmlRpc.h>

#include "rigid_body_sim/RodState.h"
#include "rigid_body_sim/RollerState.h"
#include "rigid_body_sim/Step.h"
#include "rigid_body_sim/core/world.h"
#include "rigid_body_sim/io/config_loader.h"
#include "rigid_body_sim/ros/messages.h"
#include "rigid_body_sim/ros/service_calls.h"
#include "rigid_body_sim/testing/sim_fixture.h"  // callNode, publishesHere

namespace rigid_body_sim {
namespace test {

// Every state message of every body of a world, in arrival order per body.
class StateCollector {
 public:
  StateCollector(ros::NodeHandle& nh, const World& world, const std::string& ns = "/sim") : node_(ns) {
    for (const auto& body : world.bodies()) {
      const std::string topic = ns + "/" + body.name + "/state";
      if (std::holds_alternative<Rod>(body.model)) {
        subscribe(nh, topic, rods_[body.name]);
      } else {
        subscribe(nh, topic, rollers_[body.name]);
      }
    }
  }

  // The subscriptions end before the containers their callbacks fill.
  ~StateCollector() { stop(); }

  // Waits until the node publishes every state topic to this node (publishesHere): from then on every state
  // it sends arrives.
  bool waitConnected(double timeout) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::WallTime::now() < end) {
      bool all = true;
      for (const auto& sub : subs_) all = all && publishesHere(node_, sub.getTopic());
      if (all) return true;
      ros::WallDuration(0.02).sleep();
    }
    return false;
  }

  // Waits until pred() holds (checked under the lock), at most timeout wall seconds.
  bool waitFor(const std::function<bool()>& pred, double timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    return cv_.wait_for(lock, std::chrono::duration<double>(timeout), pred);
  }

  // Waits until every body has a state with time exactly t (looked for at every message).
  bool waitAllAt(const World& world, double t, double timeout = 3.0) {
    return waitFor([&] { return allAtLocked(world, t); }, timeout);
  }

  // Waits until every body has a state at t (true), or until the node has gone: every state topic lost its
  // publisher, so whatever it sent has arrived, and its callbacks have run (false: a subscriber that fell
  // behind at real_time_factor 0 misses what the node's queues still held when it exited). nullopt when
  // neither came in time. When it returns, no callback of this collector runs any more.
  std::optional<bool> waitAllAtOrGone(const World& world, double t, double timeout) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
    while (!waitAllAt(world, t, 0.02)) {
      if (ros::WallTime::now() > end) return std::nullopt;
      if (std::any_of(subs_.begin(), subs_.end(), [](const auto& sub) { return sub.getNumPublishers() > 0; }))
        continue;
      while (!ros::getGlobalCallbackQueue()->isEmpty()) {
        if (ros::WallTime::now() > end) return std::nullopt;
        ros::WallDuration(0.02).sleep();
      }
      stop();  // waits for a callback under way
      std::lock_guard<std::mutex> lock(mutex_);
      return allAtLocked(world, t);
    }
    stop();
    return true;
  }

  // No more messages: the subscriptions end (a callback under way first finishes).
  void stop() {
    for (auto& sub : subs_) sub.shutdown();
  }

  // Waits until every body has at least one state.
  bool waitAllAny(const World& world, double timeout = 3.0) {
    return waitFor(
        [&] {
          for (const auto& body : world.bodies()) {
            if (std::holds_alternative<Rod>(body.model) ? rods_[body.name].empty()
                                                        : rollers_[body.name].empty())
              return false;
          }
          return true;
        },
        timeout);
  }

  std::vector<RodState> rod(const std::string& name) {
    std::lock_guard<std::mutex> lock(mutex_);
    return rods_[name];
  }
  std::vector<RollerState> roller(const std::string& name) {
    std::lock_guard<std::mutex> lock(mutex_);
    return rollers_[name];
  }
  std::size_t count() {
    std::lock_guard<std::mutex> lock(mutex_);
    return count_;
  }
  // Unlocked access for predicates passed to waitFor.
  std::map<std::string, std::vector<RodState>>& rodsLocked() { return rods_; }
  std::map<std::string, std::vector<RollerState>>& rollersLocked() { return rollers_; }
  std::size_t countLocked() const { return count_; }

  // Forgets every message received (the subscriptions' containers stay).
  void clear() {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto& [name, msgs] : rods_) msgs.clear();
    for (auto& [name, msgs] : rollers_) msgs.clear();
    count_ = 0;
  }

 private:
  // Appends every message of `topic` to `into` (a container of this collector's maps: it stays in place).
  template <class Msg>
  void subscribe(ros::NodeHandle& nh, const std::string& topic, std::vector<Msg>& into) {
    subs_.push_back(nh.subscribe<Msg>(
        topic, 100000,
        [this, &into](const typename Msg::ConstPtr& msg) {
          std::lock_guard<std::mutex> lock(mutex_);
          into.push_back(*msg);
          ++count_;
          cv_.notify_all();
        },
        ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay()));
  }

  // Whether every body has a state with time exactly t. A body's t never goes back, so each look reads its
  // latest states only.
  bool allAtLocked(const World& world, double t) {
    const auto has = [t](const auto& msgs) {
      for (auto m = msgs.rbegin(); m != msgs.rend() && m->t >= t; ++m) {
        if (m->t == t) return true;
      }
      return false;
    };
    for (const auto& body : world.bodies()) {
      if (!(std::holds_alternative<Rod>(body.model) ? has(rods_[body.name]) : has(rollers_[body.name])))
        return false;
    }
    return true;
  }

  std::mutex mutex_;
  std::condition_variable cv_;
  std::map<std::string, std::vector<RodState>> rods_;
  std::map<std::string, std::vector<RollerState>> rollers_;
  std::size_t count_ = 0;
  std::string node_;  // the node that publishes the states
  // Last, and so destroyed first: unsubscribing waits for a callback under way, which still finds the maps.
  std::vector<ros::Subscriber> subs_;
};

// Every line a node sends to /rosout, in the order it logged them: the node has one /rosout publisher and
// this one connection to it, so a line logged after another always arrives after it.
class NodeLog {
 public:
  explicit NodeLog(ros::NodeHandle& nh, const std::string& node = "/sim")
      : node_(node),
        sub_(nh.subscribe<rosgraph_msgs::Log>("/rosout", 10000,
                                              [this](const rosgraph_msgs::Log::ConstPtr& msg) {
                                                if (msg->name != node_) return;
                                                std::lock_guard<std::mutex> lock(mutex_);
                                                lines_.push_back(*msg);
                                                arrived_.notify_all();
                                              })) {}

  // Waits until the node publishes /rosout to this node (its lines are not lost from then on).
  bool waitConnected(double timeout) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
    while (!publishesHere(node_, "/rosout")) {
      if (ros::WallTime::now() > end) return false;
      ros::WallDuration(0.02).sleep();
    }
    return true;
  }

  // Waits until a line holding `text` has arrived (at most timeout wall seconds); then returns every line
  // before the first such one and forgets them and it. Lines logged before that one have all arrived.
  std::optional<std::vector<rosgraph_msgs::Log>> takeUntil(const std::string& text, double timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    auto found = lines_.end();
    const auto holds = [&] {
      found = std::find_if(lines_.begin(), lines_.end(), [&](const rosgraph_msgs::Log& line) {
        return line.msg.find(text) != std::string::npos;
      });
      return found != lines_.end();
    };
    if (!arrived_.wait_for(lock, std::chrono::duration<double>(timeout), holds)) return std::nullopt;
    std::vector<rosgraph_msgs::Log> before(lines_.begin(), found);
    lines_.erase(lines_.begin(), found + 1);
    return before;
  }

 private:
  std::string node_;
  std::mutex mutex_;
  std::condition_variable arrived_;
  std::vector<rosgraph_msgs::Log> lines_;
  ros::Subscriber sub_;
};

// The texts of the lines of at least `level` (rosgraph_msgs::Log::ERROR, say).
inline std::vector<std::string> textsAtLeast(const std::vector<rosgraph_msgs::Log>& lines,
                                             std::uint8_t level) {
  std::vector<std::string> texts;
  for (const auto& line : lines) {
    if (line.level >= level) texts.push_back(line.msg);
  }
  return texts;
}

// Exact comparison of every field but the header (the messages' generated operator==, so that a field added
// to the .msg is compared too).
template <class Msg>
void expectSameState(const Msg& expected, Msg got, const std::string& what) {
  got.header = expected.header;
  EXPECT_EQ(expected, got) << what;
}

inline RodState expectedRod(const World& world, const std::string& name) {
  const Body* body = const_cast<World&>(world).find(name);
  return toStateMsg(world.time(), std::get<Rod>(body->model));
}
inline RollerState expectedRoller(const World& world, const std::string& name) {
  const Body* body = const_cast<World&>(world).find(name);
  return toStateMsg(world.time(), std::get<Roller>(body->model));
}

inline std::string configPath() {
  std::string path;
  ros::param::get("~config", path);
  return path;
}

// The test's service calls, over kept connections (service_calls.h says why).
inline ServiceCalls& serviceCalls() {
  static ServiceCalls calls;
  return calls;
}

inline bool callEmpty(const std::string& service) {
  std_srvs::Empty srv;
  return serviceCalls().call(service, srv);
}

inline Step callStep(std::uint32_t steps, bool* called = nullptr) {
  Step srv;
  srv.request.steps = steps;
  const bool ok = serviceCalls().call("/sim/step", srv);
  if (called) *called = ok;
  return srv;
}

inline std::int64_t stepIndex(double t, double rate) { return std::llround(t * rate); }

// Asks the reconfigure server of `body` for these values; returns the values it shows afterwards.
inline dynamic_reconfigure::Config callReconfigure(
    const std::string& body, const std::vector<std::pair<std::string, double>>& doubles,
    const std::vector<std::pair<std::string, std::string>>& texts, bool* called) {
  dynamic_reconfigure::Reconfigure srv;
  for (const auto& [key, value] : doubles) {
    dynamic_reconfigure::DoubleParameter p;
    p.name = key;
    p.value = value;
    srv.request.config.doubles.push_back(p);
  }
  for (const auto& [key, value] : texts) {
    dynamic_reconfigure::StrParameter p;
    p.name = key;
    p.value = value;
    srv.request.config.strs.push_back(p);
  }
  *called = serviceCalls().call("/sim/" + body + "/set_parameters", srv);
  return srv.response.config;
}

// The number `key` among the values a server shows (NaN when it shows none).
inline double doubleOf(const dynamic_reconfigure::Config& config, const std::string& key) {
  for (const auto& p : config.doubles) {
    if (p.name == key) return p.value;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

// Waits until `holds` (looked at every 10 ms), at most `timeout` wall seconds.
inline bool waitUntil(const std::function<bool()>& holds, double timeout) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
  while (!holds()) {
    if (ros::WallTime::now() > end) return false;
    ros::WallDuration(0.01).sleep();
  }
  return true;
}

// A node started paused (start_paused) with a `duration`: waits until it publishes every body's state topic
// to this test (in the node's own view: from then on all it publishes there arrives), unpauses it, waits for
// the end of its run and every body's state at the duration. Returns the duration and the lines the node
// logged in its run. Use it inside ASSERT_NO_FATAL_FAILURE.
inline void runToDuration(StateCollector& collector, NodeLog& log, const World& world, double* duration,
                          std::vector<rosgraph_msgs::Log>* logged = nullptr) {
  ASSERT_TRUE(collector.waitConnected(10.0)) << "the node does not publish every state to this test";
  ASSERT_TRUE(log.waitConnected(10.0)) << "the node does not log to this test";
  ASSERT_TRUE(ros::service::waitForService("/sim/unpause", 10000));
  ASSERT_TRUE(callEmpty("/sim/unpause"));
  // The run is over when the node says so, after it published the last sample (t = duration); that sample
  // of every body arrives before the node exits.
  ASSERT_TRUE(ros::param::get("/sim/duration", *duration));
  const auto lines = log.takeUntil("the requested duration; shutting down", 40.0);
  ASSERT_TRUE(lines) << "the run did not end";
  if (logged) *logged = *lines;
  const std::optional<bool> complete = collector.waitAllAtOrGone(world, *duration, 40.0);
  ASSERT_TRUE(complete.has_value()) << "neither every body's state at t = " << *duration
                                    << " nor the node's exit";
  ASSERT_TRUE(*complete) << "the node exited before this test had every body's state at t = " << *duration;
}

// main() for a rostest gtest node: ros::init, an AsyncSpinner, then the tests.
#define RBS_ROSTEST_MAIN(node_name)       \
  int main(int argc, char** argv) {       \
    testing::InitGoogleTest(&argc, argv); \
    ros::init(argc, argv, node_name);     \
    ros::NodeHandle nh;                   \
    ros::AsyncSpinner spinner(2);         \
    spinner.start();                      \
    const int result = RUN_ALL_TESTS();   \
    spinner.stop();                       \
    ros::shutdown();                      \
    return result;                        \
  }

}  // namespace test
}  // namespace rigid_body_sim
