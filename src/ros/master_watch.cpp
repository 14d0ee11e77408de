#include "rigid_body_sim/ros/master_watch.h"

#include <chrono>

#include <ros/console.h>
#include <ros/init.h>
#include <ros/master.h>
#include <ros/param.h>
#include <ros/this_node.h>
#include <ros/xmlrpc_manager.h>

namespace rigid_body_sim {

namespace {

constexpr auto kWatchPeriod = std::chrono::seconds(1);  // how often the master is asked
constexpr auto kClockWait = std::chrono::seconds(2);    // for a /clock when /use_sim_time is true

}  // namespace

MasterView askMaster() {
  XmlRpc::XmlRpcValue args, response, payload;
  args[0] = ros::this_node::getName();
  args[1] = ros::this_node::getName();
  // execute() is false both without an answer and with an answer that is an error ("unknown node"):
  // only the answer itself (code, message, value) tells them apart.
  const bool known = ros::master::execute("lookupNode", args, response, payload, false);
  if (!known) {
    const bool answered = response.getType() == XmlRpc::XmlRpcValue::TypeArray && response.size() == 3;
    return answered ? MasterView::Forgot : MasterView::Unreachable;
  }
  const bool ours = payload.getType() == XmlRpc::XmlRpcValue::TypeString &&
                    static_cast<std::string>(payload) == ros::XMLRPCManager::instance()->getServerURI();
  return ours ? MasterView::Knows : MasterView::Forgot;
}

MasterWatch::MasterWatch(Start start, int exit_status, std::function<bool()> ending,
                         std::function<void()> forgotten)
    : start_(std::move(start)),
      exit_status_(exit_status),
      ending_(std::move(ending)),
      forgotten_(std::move(forgotten)) {}

MasterWatch::~MasterWatch() { stop(); }

void MasterWatch::start() {
  thread_ = std::thread([this] { watch(); });
}

void MasterWatch::stop() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);  // the thread, between its check and its wait
    stopped_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void MasterWatch::watch() {
  const auto started = std::chrono::steady_clock::now();
  bool clock_checked = false;
  while (!stopped_ && !ending_() && ros::ok()) {
    if (!clock_checked && std::chrono::steady_clock::now() - started >= kClockWait) {
      clock_checked = true;
      warnIfNoClock();
    }
    if (askMaster() == MasterView::Forgot) {
      // roscpp marks the shutdown before it unregisters.
      if (stopped_ || ending_() || ros::isShuttingDown() || !ros::ok()) return;
      restoreParameters();
      ROS_ERROR(
          "the ROS master at %s restarted and no longer knows this node, which cannot register again: "
          "exiting with status %d (sim.launch respawn:=true starts it afresh)",
          ros::master::getURI().c_str(), exit_status_);
      forgotten_();
      return;
    }
    std::unique_lock<std::mutex> lock(mutex_);
    wake_.wait_for(lock, kWatchPeriod, [this] { return stopped_.load(); });
  }
}

// /use_sim_time left true by an earlier launch (playback.launch sets it) and no /clock: this node stamps in
// simulated time and every node on simulated time waits for a clock that never comes. Said once.
void MasterWatch::warnIfNoClock() const {
  if (!start_.use_sim_time || start_.publishes_clock || !ros::Time::now().isZero()) return;
  ROS_WARN(
      "/use_sim_time is true but nothing publishes /clock: this node stamps in simulated time and nodes on "
      "simulated time stand still (rosparam set /use_sim_time false, or sim.launch use_sim_time:=true to "
      "have this node publish /clock)");
}

// A restarted master holds none of the parameters roslaunch set.
void MasterWatch::restoreParameters() {
  if (ros::param::has(start_.private_namespace)) return;
  ros::param::set(start_.private_namespace, start_.private_params);
  if (start_.use_sim_time && !ros::param::has("/use_sim_time")) ros::param::set("/use_sim_time", true);
}

}  // namespace rigid_body_sim
