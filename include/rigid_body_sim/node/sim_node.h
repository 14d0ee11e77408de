// sim_node: a ROS adapter around a Session (run/session.h) of the core World; physics and validation stay in
// the core and the config loader, the order of steps, samples and commands in the Session.
//
// Threads. The stepping thread owns the session, the publishers of what it hands out and the recorder: it
// steps at the pace, publishes, and between two publishing instants runs the work handed to it. Every
// callback (services, reconfigure servers, interactive markers, timers) runs on the one spinner thread: it
// hands its change of the world to the stepping thread (onStepper) and waits for the answer; then, on the
// spinner thread, the reconfigure servers and the interactive markers follow (the stepping thread never
// touches them). No lock guards the world, so no lock order exists (run/task_queue.h).
#pragma once

#include <atomic>
#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <ros/ros.h>
#include <std_srvs/Empty.h>

#include "rigid_body_sim/Delete.h"
#include "rigid_body_sim/GetConfig.h"
#include "rigid_body_sim/SetState.h"
#include "rigid_body_sim/Spawn.h"
#include "rigid_body_sim/Step.h"
#include "rigid_body_sim/ros/interactive_controls.h"
#include "rigid_body_sim/ros/master_watch.h"
#include "rigid_body_sim/ros/node_publisher.h"
#include "rigid_body_sim/ros/node_recorder.h"
#include "rigid_body_sim/ros/params.h"
#include "rigid_body_sim/ros/reconfigure_servers.h"
#include "rigid_body_sim/run/finite_guard.h"
#include "rigid_body_sim/run/session.h"
#include "rigid_body_sim/run/step_pacer.h"
#include "rigid_body_sim/run/task_queue.h"

namespace rigid_body_sim {

class SimNode {
 public:
  // The exit status after the master restarted and forgot the node (roslaunch's respawn starts it again).
  static constexpr int kMasterForgotStatus = 3;
  // The exit status after the node's own recorder (~bag) could not write (a full disk, a file-size limit).
  static constexpr int kRecordingFailedStatus = 4;

  // Loads and validates the private parameters; throws ConfigError with the one refusal line.
  SimNode(ros::NodeHandle node, ros::NodeHandle private_node);
  ~SimNode();

  // Starts the stepping thread and spins the callbacks until shutdown; returns the exit status: 0,
  // kMasterForgotStatus or kRecordingFailedStatus.
  int run();

 private:
  // A change of the world as the stepping thread answers it.
  struct Answer {
    bool accepted = false;
    std::string why;  // "ok", or the one refusal line
    double t = 0.0;   // the simulated time it applied at (its ~commands entry's t), or then
    std::optional<WorldCommand> command;  // as applied; none for a request that changes nothing
    WorldConfig config;                   // the world's after it
  };
  // Makes the command of a change from the running world: none if it changes nothing; a ConfigError is its
  // refusal.
  using BuildCommand = std::function<std::optional<WorldCommand>(const World& world)>;

  void advertise();
  // --- The one way to change the running world, from any callback: the services, the reconfigure servers,
  // the interactive markers. On the stepping thread: `build` makes the command from the running world and
  // Session::apply applies it (a publishing instant not yet published first, then the command at the current
  // step, logged (INFO) and published on ~commands); what depends on the world follows (state topics, the
  // guard, static TF, markers, the recorder). Then, on the caller's thread: the reconfigure servers and the
  // interactive markers. A refusal: one WARN line, the same line in the answer; nothing changes and nothing
  // is published on ~commands.
  Answer change(const std::string& kind, const std::string& body, const BuildCommand& build);
  Answer applyHere(const std::string& kind, const std::string& body, const BuildCommand& build);
  // After an accepted command, on the stepping thread: the guard follows the world (the sinks have). `index`
  // is the command's body's place in the world before it.
  void followWorld(const WorldCommand& command, std::size_t index);
  // A reconfigure of body `name` from its server (`unchanged_is_none`: a request that changes nothing is
  // no command) or from a drop in rviz.
  Answer reconfigure(const std::string& name, const ReconfigureServers::Reconfigured& reconfigured,
                     bool unchanged_is_none);
  // A service's change of one body: `fill` puts in what the request brings (a ConfigError refuses it); the
  // response says whether it applied, the one line if not, and (~spawn) the time it applied at.
  using FillCommand = std::function<void(WorldCommand& command)>;
  template <class Response>
  bool answerService(WorldCommand::Kind kind, const std::string& body, const FillCommand& fill,
                     Response& response);
  bool onSpawn(Spawn::Request& request, Spawn::Response& response);
  bool onDelete(Delete::Request& request, Delete::Response& response);
  bool onSetState(SetState::Request& request, SetState::Response& response);
  bool onGetConfig(GetConfig::Request& request, GetConfig::Response& response);
  // Initial conditions dropped in rviz: a reconfigure of those keys, a change like any other.
  bool onDrop(const std::string& body, const std::map<std::string, double>& initial, std::string* why);
  bool onReset(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onPause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  void publishPaused(bool paused);  // on ~paused
  bool onUnpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onStep(Step::Request& request, Step::Response& response);
  void stepPaused(std::uint64_t steps, Step::Response& response);  // on the stepping thread

  // Runs `work` on the stepping thread between two publishing instants and returns its result.
  template <class Work>
  auto onStepper(Work work) -> decltype(work()) {
    return stepper_tasks_.call(std::move(work));
  }
  void serveTasksFor(std::chrono::milliseconds wait);  // on the stepping thread: runs what comes meanwhile

  // --- The stepping thread
  void stepLoop();
  // The step hook, after every step: holds a body that became non-finite at its last finite state (the
  // one error about it), then the step's events (DEBUG).
  void afterStep(World& world);
  void waitForStart();
  // The node's own recorder could not write: the run ends with one ERROR line (kRecordingFailedStatus).
  void stopRecording(double t, const std::string& what);
  const World& world() const { return session_.world(); }  // on the stepping thread
  void anchor();  // the pace and the wall-clock stamps start from now and the current step
  double wallNow() const;

  void stopThreads();  // stops and joins the stepper and the master watch

  ros::NodeHandle node_;
  ros::NodeHandle private_node_;
  XmlRpc::XmlRpcValue start_params_;  // the private namespace as it was at the start
  NodeOptions options_;

  TaskQueue stepper_tasks_;  // the work handed to the stepping thread

  // Owned by the stepping thread (set up before it starts):
  // The world (also the running config, what ~get_config returns), sampled at every publishing instant.
  Session session_;
  StepHook after_step_;  // afterStep
  FiniteGuard guard_;
  bool paused_ = false;
  StepPacer pacer_;
  bool use_sim_time_;
  NodePublisher publisher_;                 // the session's first sink: the node's topics
  std::unique_ptr<NodeRecorder> recorder_;  // the ~bag option: every publication, lossless by construction
  ros::Publisher paused_publisher_;         // ~paused: true from ~pause (or start_paused) until ~unpause
  std::vector<ros::ServiceServer> services_;

  // Owned by the spinner thread:
  ReconfigureServers servers_;                        // ~<body>: each body's keys
  std::unique_ptr<InteractiveControls> interactive_;  // ~interactive: place and throw bodies in rviz

  std::atomic<bool> stopping_{false};
  std::atomic<int> exit_status_{0};
  std::thread stepper_;
  MasterWatch watch_;  // a thread of its own
};

}  // namespace rigid_body_sim
