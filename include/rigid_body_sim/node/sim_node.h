// sim_node: a thin ROS adapter around a Session (run/session.h) of the core World. It owns the stepping
// thread, the publishers, the reconfigure servers and the services; physics and validation stay in the core
// and the config loader, the order of steps, samples and commands in the Session.
#pragma once

#include <atomic>
#include <condition_variable>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <dynamic_reconfigure/server.h>
#include <ros/ros.h>
#include <std_srvs/Empty.h>
#include <tf2_msgs/TFMessage.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include "rigid_body_sim/Delete.h"
#include "rigid_body_sim/GetConfig.h"
#include "rigid_body_sim/RodReconfigureConfig.h"
#include "rigid_body_sim/RollerReconfigureConfig.h"
#include "rigid_body_sim/SetState.h"
#include "rigid_body_sim/Spawn.h"
#include "rigid_body_sim/Step.h"
#include "rigid_body_sim/ros/bag_recorder.h"
#include "rigid_body_sim/ros/interactive_controls.h"
#include "rigid_body_sim/ros/params.h"
#include "rigid_body_sim/ros/snapshot.h"
#include "rigid_body_sim/run/finite_guard.h"
#include "rigid_body_sim/run/session.h"
#include "rigid_body_sim/run/step_pacer.h"

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

  // The one way to change the running world (the services, the reconfigure servers, the interactive tools):
  // Session::apply, which publishes a publishing instant not yet published first, then applies `command` at
  // the current step (command.step is set there), logs it (INFO) and publishes it on ~commands; then what
  // depends on the world follows (state topics, reconfigure servers, static TF, markers). *t is the
  // simulated time it applied at, its ~commands entry's t. A refusal returns false: one WARN line, the same
  // line in *why; nothing changes and nothing is published on ~commands; *t is the time then.
  bool applyCommand(WorldCommand command, std::string* why = nullptr, double* t = nullptr);

 private:
  // A publisher whose subscribers are counted as they come and go (the count shared with its callbacks: a
  // deleted body's may still run). Publisher::getNumSubscribers looks the topic up among all of the node's
  // publications, and once per body per publication that was most of the node's work with 1000 bodies.
  struct CountedPublisher {
    ros::Publisher publisher;
    std::shared_ptr<std::atomic<int>> subscribers;
    bool watched() const { return subscribers && *subscribers > 0; }
  };
  template <class Message>
  CountedPublisher advertiseCounted(ros::NodeHandle& node, const std::string& topic, std::uint32_t queue);

  using RodServer = dynamic_reconfigure::Server<RodReconfigureConfig>;
  using RollerServer = dynamic_reconfigure::Server<RollerReconfigureConfig>;
  struct BodyServer {  // one of the two, by the body's type
    std::unique_ptr<RodServer> rod;
    std::unique_ptr<RollerServer> roller;
  };

  void advertise();
  void advertiseState(const Body& body);  // its publisher and subscriber count, at the end of the lists
  void startReconfigureServers();         // every body's that has none yet, after the first publication
  void startReconfigureServer(const BodyConfig& body);
  template <class Config, class Request>
  void onReconfigure(const std::string& name, Request& request);
  // The node's side of the Session, called by it with mutex_ held: write publishes the states of a count
  // (publishLocked), applied logs a command and publishes it on ~commands (publishCommandLocked).
  class Publication : public SampleSink {
   public:
    explicit Publication(SimNode& node) : node_(node) {}
    void write(const World& world) override;
    void applied(const WorldCommand& command, std::size_t index, const World& world) override;

   private:
    SimNode& node_;
  };

  // Builds a command with `build` (which may throw ConfigError: a refusal like any other) and applies it.
  template <class Build>
  bool applyBuilt(const std::string& kind, const std::string& body, Build build, std::string* why,
                  double* t = nullptr);
  bool refuse(const std::string& kind, const std::string& body, const std::string& reason, std::string* why);
  // On ~commands as number `index` (header.seq; 0: the config at the start); recorded after the config.
  void publishCommandLocked(const WorldCommand& command, std::size_t index);
  // After an accepted command: publishers, the guard and the scene follow the world. Caller holds mutex_.
  void followWorldLocked(const WorldCommand& command, const WorldConfig& before);
  // After an accepted command, without mutex_ (a server's first callback takes it): reconfigure servers.
  void followWorldServers(const WorldCommand& command);
  bool onSpawn(Spawn::Request& request, Spawn::Response& response);
  bool onDelete(Delete::Request& request, Delete::Response& response);
  bool onSetState(SetState::Request& request, SetState::Response& response);
  bool onGetConfig(GetConfig::Request& request, GetConfig::Response& response);
  // Initial conditions dropped in rviz: a reconfigure of those keys, through applyCommand like any other.
  bool onDrop(const std::string& body, const std::map<std::string, double>& initial, std::string* why);
  bool onReset(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onPause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  void publishPaused(bool paused);  // on ~paused
  bool onUnpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onStep(Step::Request& request, Step::Response& response);

  void stepLoop();
  // Every second: does the master still know this node? When a restarted master does not, puts the
  // parameters this node started from back on it (for the respawned node) and shuts down.
  void watchMaster();
  void warnIfNoClock();
  void stopThreads();  // stops and joins the stepper and the watcher
  void restoreParameters();
  // The step hook, after every step: holds a body that became non-finite at its last finite state (the
  // one error about it), then the step's events (DEBUG). Caller holds mutex_.
  void afterStepLocked(World& world);
  // The states, TF, markers and /clock of the current count; the same into the recorder.
  void publishLocked();
  void publishClockLocked();
  // Trail pieces and labels on ~markers at marker instants, built only while someone subscribes.
  void publishMarkersLocked(const ros::Time& stamp);
  void publishMarkersNowLocked();
  // The fixed frames on /tf_static (and <ns>/tf_static).
  void publishStaticTransformsLocked();
  // The fixed frames and the latched ~scene.
  void publishSceneLocked();
  // After the set of bodies or a body's look changed: new placements; the fixed frames and, if it changed,
  // the scene are sent again. Trails go on by body name.
  void rebuildSceneLocked();
  void waitForStartLocked(std::unique_lock<std::mutex>& lock);
  // Every write of the node's own recorder: a write error ends the recording and the run with one ERROR
  // line (kRecordingFailedStatus), never the process.
  void recordLocked(const std::function<void(BagRecorder&)>& write);
  ros::Time stampOf(double t) const;
  const World& world() const { return session_.world(); }  // caller holds mutex_
  void anchorLocked();  // the pace and the wall-clock stamps start from now and the current step
  double wallNow() const;

  ros::NodeHandle node_;
  ros::NodeHandle private_node_;
  XmlRpc::XmlRpcValue start_params_;  // the private namespace as it was at the start
  NodeOptions options_;

  std::mutex mutex_;  // guards everything below that the stepping thread touches
  // The world (also the running config, what ~get_config returns), sampled at every publishing instant.
  Session session_;
  Publication publication_{*this};  // the session's one sink
  StepHook after_step_;             // afterStepLocked
  FiniteGuard guard_;
  std::int64_t steps_per_markers_;  // a whole number of publishing intervals
  bool markers_watched_ = false;    // whether ~markers had a subscriber at the last publication
  ros::Time last_clock_;            // the last /clock published (zero: none yet)
  ros::Time last_tf_stamp_;         // the stamp of the last transforms on /tf
  bool paused_ = false;
  StepPacer pacer_;
  std::condition_variable wake_;
  std::unique_ptr<SnapshotBuilder> snapshots_;
  std::unique_ptr<BagRecorder> recorder_;  // the ~bag option: every publication, lossless by construction
  ros::Time stamp_anchor_;    // the wall-clock stamp of simulated time time_anchor_ (without use_sim_time)
  double time_anchor_ = 0.0;  // s
  bool use_sim_time_ = false;

  ros::Publisher command_publisher_;
  ros::Publisher paused_publisher_;  // ~paused: true from ~pause (or start_paused) until ~unpause
  CountedPublisher marker_publisher_;
  ros::Publisher scene_publisher_;
  ros::WallTimer scene_resend_timer_;             // once a second: the scene again for a viewer that joined
  std::atomic<bool> scene_viewer_joined_{false};  // since the last tick
  std::atomic<bool> scene_resend_due_{false};     // a viewer joined before the last tick
  ros::Publisher clock_publisher_;
  CountedPublisher tf_publisher_;       // /tf, as tf2_ros::TransformBroadcaster sends it
  CountedPublisher namespace_tf_;       // in a namespace: <ns>/tf, a copy of what goes to /tf
  ros::Publisher namespace_tf_static_;  // and <ns>/tf_static
  std::vector<CountedPublisher> state_publishers_;
  tf2_ros::StaticTransformBroadcaster static_broadcaster_;
  std::vector<ros::ServiceServer> services_;
  // The servers' own (held while they call back; updateConfig needs it to be ours). applyCommand takes it
  // before mutex_, always in this order: a reconfigure callback arrives holding it.
  boost::recursive_mutex reconfigure_mutex_;
  std::map<std::string, BodyServer> servers_;         // by body name
  std::unique_ptr<InteractiveControls> interactive_;  // ~interactive: place and throw bodies in rviz

  std::atomic<bool> stopping_{false};
  std::atomic<int> exit_status_{0};
  std::thread stepper_;
  std::thread watcher_;
  std::mutex watch_mutex_;  // the watcher's wait, cut short by stopThreads
  std::condition_variable watch_wake_;
};

}  // namespace rigid_body_sim
