// The master watch (ros/master_watch.h) under rostest's master, without sim_node (master_watch.test): the
// test makes the master forget this node by unregistering everything it registered, as a restarted master
// has. A watch of a running node then puts the node's parameters (and /use_sim_time) back, and says so once;
// a watch of a node that is ending does neither.
#include <ros/master.h>
#include <ros/xmlrpc_manager.h>

#include "node_test_util.h"
#include "rigid_body_sim/ros/master_watch.h"

using namespace rigid_body_sim;

namespace {

constexpr double kTimeout = 20.0;         // wall seconds for any wait
const char* const kWatched = "/watched";  // the private namespace of the node watched

// The master forgets this node: every topic and service it lists for it is unregistered.
void forgetThisNode() {
  XmlRpc::XmlRpcValue args, state, payload;
  args[0] = ros::this_node::getName();
  ASSERT_TRUE(ros::master::execute("getSystemState", args, state, payload, true));
  const std::string me = ros::this_node::getName();
  const std::string api = ros::XMLRPCManager::instance()->getServerURI();
  const char* const unregister[] = {"unregisterPublisher", "unregisterSubscriber", "unregisterService"};
  for (int kind = 0; kind < 3; ++kind) {
    for (int i = 0; i < payload[kind].size(); ++i) {
      XmlRpc::XmlRpcValue& entry = payload[kind][i];  // [name, [node, ...]]
      for (int n = 0; n < entry[1].size(); ++n) {
        if (static_cast<std::string>(entry[1][n]) != me) continue;
        XmlRpc::XmlRpcValue call, response, result;
        call[0] = me;
        call[1] = entry[0];
        call[2] = api;
        if (kind == 2) {  // a service is unregistered with its own rosrpc URI
          XmlRpc::XmlRpcValue lookup, uri;
          XmlRpc::XmlRpcValue name;
          name[0] = me;
          name[1] = entry[0];
          ASSERT_TRUE(ros::master::execute("lookupService", name, lookup, uri, true));
          call[2] = uri;
        }
        ASSERT_TRUE(ros::master::execute(unregister[kind], call, response, result, true)) << unregister[kind];
      }
    }
  }
  // A parameter roscpp's /rosout appender caches at the first line logged (ROS_INFO below): the master
  // lists the node for it too, but not in getSystemState.
  XmlRpc::XmlRpcValue call, response, result;
  call[0] = me;
  call[1] = api;
  call[2] = "/rosout_disable_topics_generation";
  ASSERT_TRUE(ros::master::execute("unsubscribeParam", call, response, result, true));
}

XmlRpc::XmlRpcValue startParams() {
  XmlRpc::XmlRpcValue params;
  params["rate"] = 500.0;
  params["world_frame"] = std::string("map");
  return params;
}

MasterWatch::Start startOfWatched() { return {kWatched, startParams(), true, false}; }

// Runs first: it makes the master forget this node for good.
TEST(MasterWatch, PutsTheParametersBackWhenTheMasterForgetsTheNode) {
  std::atomic<int> forgotten{0};
  const auto running = [] { return false; };
  const auto forget = [&] { ++forgotten; };
  MasterWatch watch(startOfWatched(), 3, running, forget);
  watch.start();
  ROS_INFO("the master forgets this node");  // the /rosout appender's parameter cached now, not later
  ASSERT_EQ(askMaster(), MasterView::Knows);
  ros::param::del(kWatched);
  ros::param::del("/use_sim_time");
  forgetThisNode();
  ASSERT_EQ(askMaster(), MasterView::Forgot);
  ASSERT_TRUE(test::waitUntil([&] { return forgotten > 0; }, kTimeout)) << "the watch saw no restart";
  watch.stop();
  EXPECT_EQ(forgotten, 1);
  double rate = 0.0;
  std::string frame;
  EXPECT_TRUE(ros::param::get(std::string(kWatched) + "/rate", rate));
  EXPECT_EQ(rate, 500.0);
  EXPECT_TRUE(ros::param::get(std::string(kWatched) + "/world_frame", frame));
  EXPECT_EQ(frame, "map");
  bool use_sim_time = false;
  EXPECT_TRUE(ros::param::get("/use_sim_time", use_sim_time));
  EXPECT_TRUE(use_sim_time);
}

// A node ending (its duration done, Ctrl-C) when the master no longer lists it: no restart.
TEST(MasterWatch, AnEndingNodeIsNoRestart) {
  ASSERT_EQ(askMaster(), MasterView::Forgot) << "the first test made the master forget this node";
  ros::param::del(kWatched);
  std::atomic<int> asked{0};
  std::atomic<int> forgotten{0};
  // Running when the watch looks first, ending once it has found the node forgotten.
  const auto ending = [&] { return ++asked > 1; };
  const auto forget = [&] { ++forgotten; };
  MasterWatch watch(startOfWatched(), 3, ending, forget);
  watch.start();
  ASSERT_TRUE(test::waitUntil([&] { return asked >= 2; }, kTimeout));
  watch.stop();
  EXPECT_EQ(forgotten, 0);
  EXPECT_FALSE(ros::param::has(kWatched)) << "the parameters were put back for a node that ended";
}

}  // namespace

RBS_ROSTEST_MAIN("test_node_master_watch")
