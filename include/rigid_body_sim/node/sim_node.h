// sim_node: a ROS adapter around a Session (run/session.h) of the core World; physics and validation stay in
// the core and the config loader, the order of steps, samples and commands in the Session. Its parts: the
// topics (ros/node_publisher.h) and the ~bag recording (ros/node_recorder.h) are the Session's sinks; the
// services (ros/node_services.h), the reconfigure servers (ros/reconfigure_servers.h), the master watch
// (ros/master_watch.h). The node holds the stepping thread and the one path for every change.
//
// Threads. The stepping thread owns the session and its sinks: it steps at the pace, publishes, and between
// two publishing instants runs the work handed to it. Every callback (services, reconfigure servers,
// interactive markers, timers) runs on the one spinner thread: it hands its change of the world to the
// stepping thread (onStepper) and waits for the answer; then, on the spinner thread, the reconfigure servers
// and the interactive markers follow. No lock guards the world, so no lock order exists (run/task_queue.h).
#pragma once

#include <atomic>
#include <chrono>
#include <map>
#include <memory>
#include <string>
#include <thread>

#include <ros/ros.h>

#include "rigid_body_sim/ros/interactive_controls.h"
#include "rigid_body_sim/ros/master_watch.h"
#include "rigid_body_sim/ros/node_publisher.h"
#include "rigid_body_sim/ros/node_recorder.h"
#include "rigid_body_sim/ros/node_services.h"
#include "rigid_body_sim/ros/params.h"
#include "rigid_body_sim/ros/reconfigure_servers.h"
#include "rigid_body_sim/run/finite_guard.h"
#include "rigid_body_sim/run/session.h"
#include "rigid_body_sim/run/step_pacer.h"
#include "rigid_body_sim/run/task_queue.h"

namespace rigid_body_sim {

class SimNode : private BodyStepObserver {
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
  // --- The one way to change the running world, from any callback (services, reconfigure servers,
  // interactive markers). On the stepping thread (applyHere): `build` makes the command from the running
  // world, Session::apply applies it and its sinks follow, then the guard. Then, on the caller's thread: the
  // reconfigure servers and the interactive markers. A refusal: one WARN line, the same in the answer.
  ChangeAnswer change(const std::string& kind, const std::string& body, const BuildCommand& build);
  ChangeAnswer applyHere(const std::string& kind, const std::string& body, const BuildCommand& build);
  // After an accepted command: the guard follows the world. `index`: the body's place before it.
  void followWorld(const WorldCommand& command, std::size_t index);
  // A reconfigure of body `name` from its server (`unchanged_is_none`: a request that changes nothing is
  // no command) or from a drop in rviz.
  ChangeAnswer reconfigure(const std::string& name, const ReconfigureServers::Reconfigured& reconfigured,
                           bool unchanged_is_none);
  bool onDrop(const std::string& body, const std::map<std::string, double>& initial, std::string* why);
  void setPaused(bool paused);  // ~pause and ~unpause, on the stepping thread
  void stepPaused(std::uint64_t steps, Step::Response& response);  // on the stepping thread

  // Runs `work` on the stepping thread between two publishing instants and returns its result.
  template <class Work>
  auto onStepper(Work work) -> decltype(work()) {
    return stepper_tasks_.call(std::move(work));
  }
  void serveTasksFor(std::chrono::milliseconds wait);  // on the stepping thread: runs what comes meanwhile
  void serveTasksWhileSubscribersTake();  // the end of a duration: until subscribers take nothing more

  // --- The stepping thread
  void stepLoop();
  // The step hook: the NaN guard (one ERROR line per body it holds), then the step's events (DEBUG).
  // World::step's observer: the guard (and, in a test's build, its fault) on the bodies after each step.
  void afterUnsureStep(std::size_t index, Body& body) override;
  void afterBodiesStep(std::vector<Body>& bodies) override;
  void movedByWorld(std::size_t index, Body& body) override;  // the guard keeps it
  void afterStep(World& world);
  void waitForStart();
  // The node's own recorder could not write: the run ends with one ERROR line (kRecordingFailedStatus).
  std::vector<Event> runEventMessages() const;  // ~get_events: the run's events as messages
  void stopRecording(double t, const std::string& what);
  const World& world() const { return session_.world(); }  // on the stepping thread
  void anchor();       // the pace and the wall-clock stamps start from now and the current step
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

  // Owned by the spinner thread:
  ReconfigureServers servers_;                        // ~<body>: each body's keys
  std::unique_ptr<InteractiveControls> interactive_;  // ~interactive: place and throw bodies in rviz

  std::atomic<bool> stopping_{false};
  std::atomic<int> exit_status_{0};
  std::thread stepper_;
  MasterWatch watch_;      // a thread of its own
  NodeServices services_;  // their callbacks on the spinner thread
};

}  // namespace rigid_body_sim
