// Whether the ROS master still knows this process. roscpp registers a node, its topics and services once:
// a master that restarts (a new process at the same URI) knows nothing of them, and the node, unlisted
// and unreachable, would go on for nothing. roscpp cannot register a running node again, so the node
// watches for this and ends (sim.launch respawn:=true then starts it afresh).
#pragma once

#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include <xmlrpcpp/XmlRpcValue.h>

namespace rigid_body_sim {

enum class MasterView {
  Knows,        // the master lists this node at this process's XML-RPC address
  Forgot,       // the master answers but lists no such node, or another process under its name
  Unreachable,  // no answer (the master is down, or restarting): nothing to decide yet
};

// Asks the master (lookupNode of this node's own name); a few milliseconds, no retry.
MasterView askMaster();

// A thread that asks the master every second. When a restarted master no longer knows the node, it puts
// the parameters the node started from back on it (unless something has set them meanwhile: the respawned
// node starts on the same config), logs one ERROR line saying the node exits with `exit_status`, calls
// `forgotten` and ends. A node that is ending (`ending`: its duration done, Ctrl-C) unregisters itself, and
// a master that then forgets it is no restart. Once, two seconds after the start: a WARN line when
// /use_sim_time is true and no /clock has come.
class MasterWatch {
 public:
  struct Start {
    std::string private_namespace;       // the node's
    XmlRpc::XmlRpcValue private_params;  // as they were at the start
    bool use_sim_time = false;           // /use_sim_time was true at the start
    bool publishes_clock = false;        // the node itself publishes /clock
  };
  MasterWatch(Start start, int exit_status, std::function<bool()> ending, std::function<void()> forgotten);
  ~MasterWatch();  // stop()
  MasterWatch(const MasterWatch&) = delete;
  MasterWatch& operator=(const MasterWatch&) = delete;

  void start();
  void stop();  // wakes the thread and joins it

 private:
  void watch();
  void warnIfNoClock() const;
  void restoreParameters();

  Start start_;
  int exit_status_;
  std::function<bool()> ending_;
  std::function<void()> forgotten_;
  std::atomic<bool> stopped_{false};
  std::mutex mutex_;  // the thread's wait, cut short by stop()
  std::condition_variable wake_;
  std::thread thread_;
};

}  // namespace rigid_body_sim
