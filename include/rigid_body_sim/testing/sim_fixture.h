// Helpers for another package's rostests (gtest nodes) against rigid_body_sim's node, the C++ twin of the
// Python module rigid_body_sim.testing. They start nothing: the .test file's sim.launch starts the node, and
// these only subscribe to it, call its services and read its parameters, by the names of the node's
// interface (docs/DESIGN.md). Every wait has a deadline in wall seconds; each helper answers an
// AssertionResult that says, on failure, what it saw:
//
//   rigid_body_sim::SimFixture sim;                                 // the node sim.launch starts: /sim
//   rigid_body_sim::StateLog<rigid_body_sim::RollerState> sphere(sim, "sphere");
//   ASSERT_TRUE(sphere.waitConnected());
//   ASSERT_TRUE(sim.step(1000));                                    // start_paused:=true held it at t = 0
//   rigid_body_sim::RollerState state;
//   ASSERT_TRUE(sphere.waitFor(1.0, &state));                       // the first state at t >= 1 s
//   rigid_body_sim::EventLog events(sim);                           // what happens, as it happens
//   rigid_body_sim::Event finished;
//   ASSERT_TRUE(events.waitFor("finished", "sphere", &finished));   // its exact instant: finished.t
//
// Header-only; the states arrive on a spinner thread of the log's own, whatever the test's main spins. The
// test's main keeps a ros::NodeHandle for as long as the tests run (roscpp ends the node with the last one).
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <limits>
#include <mutex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <dynamic_reconfigure/Reconfigure.h>
#include <gtest/gtest.h>
#include <ros/callback_queue.h>
#include <ros/master.h>
#include <ros/network.h>
#include <ros/ros.h>
#include <std_srvs/Empty.h>
#include <xmlrpcpp/XmlRpc.h>

#include "rigid_body_sim/Event.h"
#include "rigid_body_sim/GetConfig.h"
#include "rigid_body_sim/GetEvents.h"
#include "rigid_body_sim/RodState.h"
#include "rigid_body_sim/RollerState.h"
#include "rigid_body_sim/Step.h"
#include "rigid_body_sim/ros/service_calls.h"

// In rigid_body_sim itself, not in a namespace `testing`: a test's `using namespace rigid_body_sim` would
// make gtest's `testing::` ambiguous.
namespace rigid_body_sim {

constexpr double kFixtureDeadline = 10.0;  // wall seconds of every wait unless told otherwise
// A state's t is a step count over rate: the one meant at t may come out a rounding below it.
constexpr double kStateTimeTolerance = 1e-9;

// Calls `method` of a node's own XML-RPC API (with this node as the caller); false if that fails.
inline bool callNode(const std::string& node, const std::string& method, XmlRpc::XmlRpcValue& result) {
  XmlRpc::XmlRpcValue args, lookup, payload;
  args[0] = ros::this_node::getName();
  args[1] = node;
  if (!ros::master::execute("lookupNode", args, lookup, payload, false)) return false;
  std::string host;
  std::uint32_t port = 0;
  if (!ros::network::splitURI(static_cast<std::string>(payload), host, port)) return false;
  XmlRpc::XmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
  XmlRpc::XmlRpcValue caller;
  caller[0] = ros::this_node::getName();
  return client.execute(method.c_str(), caller, result) &&
         result.getType() == XmlRpc::XmlRpcValue::TypeArray && result.size() >= 3;
}

// Whether `node` has a connection of its own that publishes `topic` to this node (its getBusInfo). From then
// on all it publishes there reaches this node. A subscription's publisher count alone is no proof: roscpp
// counts a publisher once it has sent its request, before the publisher has taken it (what the publisher
// sends in between is lost), and it counts this node's own publisher of the topic (every node publishes
// /rosout).
inline bool publishesHere(const std::string& node, const std::string& topic) {
  XmlRpc::XmlRpcValue result;
  if (!callNode(node, "getBusInfo", result)) return false;
  XmlRpc::XmlRpcValue& connections = result[2];  // [id, peer, direction, transport, topic, connected, ...]
  for (int i = 0; i < connections.size(); ++i) {
    XmlRpc::XmlRpcValue& c = connections[i];
    if (c.size() >= 6 && static_cast<std::string>(c[1]) == ros::this_node::getName() &&
        static_cast<std::string>(c[2]) == "o" && static_cast<std::string>(c[4]) == topic &&
        static_cast<bool>(c[5]))
      return true;
  }
  return false;
}

// The running node `name` (sim.launch's: /sim; with ns:=left, /left/sim).
class SimFixture {
 public:
  explicit SimFixture(std::string name = "/sim", double deadline = kFixtureDeadline)
      : name_(std::move(name)), deadline_(deadline) {}

  const std::string& name() const { return name_; }
  double deadline() const { return deadline_; }

  // A world key of the config (gravity, rate, publish_rate, world_frame) or a node option, as the launch
  // loaded it: <node>/<key>.
  template <class T>
  ::testing::AssertionResult param(const std::string& key, T* value) const {
    return get(name_ + "/" + key, value);
  }
  // A body's key as the config gave it: <node>/bodies/<body>/<key>. A key the config leaves out is not
  // there (its default applies; getConfig has every key in use); `set` does not change it.
  template <class T>
  ::testing::AssertionResult bodyParam(const std::string& body, const std::string& key, T* value) const {
    return get(name_ + "/bodies/" + body + "/" + key, value);
  }

  // The events of the current run so far (since the start or the last reset), oldest first (~get_events).
  ::testing::AssertionResult getEvents(std::vector<Event>* events) const {
    GetEvents srv;
    auto called = call("get_events", srv);
    if (called) *events = srv.response.events;
    return called;
  }
  // The world as it runs now, every key with its value in use, as a config file (~get_config).
  ::testing::AssertionResult getConfig(std::string* yaml) const {
    GetConfig srv;
    auto called = call("get_config", srv);
    if (called) *yaml = srv.response.yaml;
    return called;
  }

  ::testing::AssertionResult pause() const { return callEmpty("pause"); }
  ::testing::AssertionResult unpause() const { return callEmpty("unpause"); }
  // Every body back to its initial conditions; simulated time goes on.
  ::testing::AssertionResult reset() const { return callEmpty("reset"); }

  // `steps` physics steps while paused; `t`: the simulated time after them. A refusal is a failure.
  ::testing::AssertionResult step(std::uint32_t steps, double* t = nullptr) const {
    Step srv;
    srv.request.steps = steps;
    auto called = call("step", srv);
    if (!called) return called;
    if (!srv.response.success) {
      return ::testing::AssertionFailure()
             << name_ << "/step " << steps << " refused: " << srv.response.message;
    }
    if (t) *t = srv.response.t;
    return ::testing::AssertionSuccess();
  }

  // A body's key through its reconfigure server, as `dynparam set` does (the one path of every change): a
  // number key takes `value`, a text key (shape, integrator, substeps) the text overload. A value the node
  // refused (the server then shows the one in use) is a failure.
  ::testing::AssertionResult set(const std::string& body, const std::string& key, double value) const {
    return setKey(body, key, value, &dynamic_reconfigure::Config::doubles, "number");
  }
  ::testing::AssertionResult set(const std::string& body, const std::string& key,
                                 const std::string& value) const {
    return setKey(body, key, value, &dynamic_reconfigure::Config::strs, "text");
  }

 private:
  template <class T>
  static ::testing::AssertionResult get(const std::string& name, T* value) {
    if (ros::param::get(name, *value)) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "no parameter " << name << " of that type (a key the config "
                                         << "leaves out is not there: getConfig has every key in use)";
  }

  template <class Service>
  ::testing::AssertionResult call(const std::string& service, Service& srv) const {
    const std::string full = name_ + "/" + service;
    if (!ros::service::waitForService(full, static_cast<int>(deadline_ * 1000))) {
      return ::testing::AssertionFailure() << "no service " << full << " within " << deadline_ << " s";
    }
    if (!calls_.call(full, srv)) return ::testing::AssertionFailure() << full << " did not answer";
    return ::testing::AssertionSuccess();
  }

  ::testing::AssertionResult callEmpty(const std::string& service) const {
    std_srvs::Empty srv;
    return call(service, srv);
  }

  // `value` into the request's list of its kind (doubles, strs); then the server must show it in that list.
  // A list of a reconfigure config (a name: clang-format 14 and 19 space `Config::*list` apart).
  template <class List>
  using ConfigList = List dynamic_reconfigure::Config::*;

  template <class List, class Value>
  ::testing::AssertionResult setKey(const std::string& body, const std::string& key, const Value& value,
                                    ConfigList<List> list, const char* kind) const {
    typename List::value_type parameter;
    parameter.name = key;
    parameter.value = value;
    dynamic_reconfigure::Reconfigure srv;
    (srv.request.config.*list).push_back(parameter);
    auto called = call(body + "/set_parameters", srv);
    if (!called) return called;
    for (const auto& shown : srv.response.config.*list) {
      if (shown.name != key) continue;
      if (shown.value == value) return ::testing::AssertionSuccess();
      return ::testing::AssertionFailure()
             << name_ << "/" << body << " refused " << key << " = " << value << ": it shows " << key << " = "
             << shown.value << " (the node's WARN line says why)";
    }
    return ::testing::AssertionFailure() << name_ << "/" << body << " has no " << kind << " key " << key;
  }

  std::string name_;
  double deadline_;
  mutable ServiceCalls calls_;  // a fixture's calls come from its test's thread
};

// Every message of one topic of the node from the subscription on, in the order they came; the base of
// StateLog and EventLog.
template <class Message>
class MessageLog {
 public:
  MessageLog(const SimFixture& sim, std::string topic)
      : node_(sim.name()), topic_(std::move(topic)), deadline_(sim.deadline()), spinner_(1, &queue_) {
    nh_.setCallbackQueue(&queue_);
    subscriber_ = nh_.subscribe<Message>(topic_, 10000, [this](const typename Message::ConstPtr& message) {
      const std::lock_guard<std::mutex> lock(mutex_);
      messages_.push_back(*message);
      arrived_.notify_all();
    });
    spinner_.start();
  }
  ~MessageLog() {
    subscriber_.shutdown();
    spinner_.stop();
  }
  MessageLog(const MessageLog&) = delete;
  MessageLog& operator=(const MessageLog&) = delete;

  // Until the node publishes the topic to this node (publishesHere): every message from then on arrives.
  ::testing::AssertionResult waitConnected() {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(deadline_);
    while (!publishesHere(node_, topic_)) {
      if (std::chrono::steady_clock::now() > end || !ros::ok()) {
        return ::testing::AssertionFailure()
               << node_ << " does not publish " << topic_ << " to this node within " << deadline_
               << " s (is the node running?)";
      }
      std::unique_lock<std::mutex> lock(mutex_);
      arrived_.wait_for(lock, std::chrono::milliseconds(10));
    }
    return ::testing::AssertionSuccess();
  }

  std::vector<Message> messages() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return messages_;
  }

 protected:
  // Until a message received satisfies `wanted`: the first such into `found`; else, after the deadline, a
  // failure naming `what` and the number received.
  template <class Wanted>
  ::testing::AssertionResult waitUntil(const Wanted& wanted, Message* found, const std::string& what) {
    std::unique_lock<std::mutex> lock(mutex_);
    const auto first = [&]() -> const Message* {
      for (const Message& message : messages_) {
        if (wanted(message)) return &message;
      }
      return nullptr;
    };
    if (!arrived_.wait_for(lock, std::chrono::duration<double>(deadline_),
                           [&] { return first() != nullptr; })) {
      std::ostringstream last;
      if (messages_.empty()) {
        last << "none at all";
      } else {
        last << "the last at t = " << messages_.back().t << " s of " << messages_.size();
      }
      return ::testing::AssertionFailure()
             << "no " << what << " on " << topic_ << " within " << deadline_ << " s (" << last.str()
             << "): the simulation ended or died early, "
             << "or is paused";
    }
    *found = *first();
    return ::testing::AssertionSuccess();
  }

 private:
  std::string node_;
  std::string topic_;
  double deadline_;
  mutable std::mutex mutex_;
  std::condition_variable arrived_;
  std::vector<Message> messages_;
  ros::CallbackQueue queue_;
  ros::AsyncSpinner spinner_;
  ros::NodeHandle nh_;  // its own: the subscription lives as long as the log
  ros::Subscriber subscriber_;
};

// Every state of one body from the subscription on, in the order they came. State: the body's type's state
// message (RodState, RollerState, BlockState).
template <class State>
class StateLog : public MessageLog<State> {
 public:
  StateLog(const SimFixture& sim, const std::string& body)
      : MessageLog<State>(sim, sim.name() + "/" + body + "/state") {}

  // The first state at or after simulated time t, into `state`; a failure, saying the last state's t, if
  // none comes within the deadline (the simulation ended, died or is paused).
  ::testing::AssertionResult waitFor(double t, State* state) {
    std::ostringstream what;
    what << "state at t >= " << t << " s";
    return this->waitUntil([t](const State& s) { return s.t >= t - kStateTimeTolerance; }, state, what.str());
  }

  std::vector<State> states() const { return this->messages(); }
};

// Every event of the node (<node>/events) from the subscription on, in the order they came: subscribe before
// the node steps (sim.launch start_paused:=true) to miss none; SimFixture::getEvents has those of the
// current run so far.
class EventLog : public MessageLog<Event> {
 public:
  explicit EventLog(const SimFixture& sim) : MessageLog<Event>(sim, sim.name() + "/events") {}

  // The first event of `kind` (of `body`, unless empty) into `event`; a failure if none comes within the
  // deadline.
  ::testing::AssertionResult waitFor(const std::string& kind, const std::string& body, Event* event) {
    return waitUntil([&](const Event& e) { return e.kind == kind && (body.empty() || e.body == body); },
                     event, "event " + kind + (body.empty() ? "" : " of " + body));
  }
};

// A number an event carries (its values, else its state fields) by name; NaN when it has none.
inline double eventNumber(const Event& event, const std::string& name) {
  for (const auto* values : {&event.values, &event.state}) {
    for (const auto& value : *values) {
      if (value.name == name) return value.number;
    }
  }
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace rigid_body_sim
