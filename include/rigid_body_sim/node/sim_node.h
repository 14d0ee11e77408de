// sim_node: a thin ROS adapter around the core World. It owns the stepping thread, the publishers, the
// reconfigure servers and the services; physics and validation stay in the core and the config loader.
#pragma once

#include <atomic>
#include <condition_variable>
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
#include <tf2_ros/transform_broadcaster.h>

#include "rigid_body_sim/RodReconfigureConfig.h"
#include "rigid_body_sim/RollerReconfigureConfig.h"
#include "rigid_body_sim/Step.h"
#include "rigid_body_sim/core/world.h"
#include "rigid_body_sim/io/finite_guard.h"
#include "rigid_body_sim/io/step_pacer.h"
#include "rigid_body_sim/ros/bag_recorder.h"
#include "rigid_body_sim/ros/params.h"
#include "rigid_body_sim/ros/snapshot.h"

namespace rigid_body_sim {

class SimNode {
 public:
  // The exit status after the master restarted and forgot the node (roslaunch's respawn starts it again).
  static constexpr int kMasterForgotStatus = 3;

  // Loads and validates the private parameters; throws ConfigError with the one refusal line.
  SimNode(ros::NodeHandle node, ros::NodeHandle private_node);
  ~SimNode();

  // Starts the stepping thread and spins the callbacks until shutdown; returns the exit status: 0, or
  // kMasterForgotStatus.
  int run();

 private:
  using RodServer = dynamic_reconfigure::Server<RodReconfigureConfig>;
  using RollerServer = dynamic_reconfigure::Server<RollerReconfigureConfig>;

  void advertise();
  void startReconfigureServers();
  template <class Model, class Config, class Request>
  void reconfigure(std::size_t index, Request& request);
  bool onReset(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onPause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onUnpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onStep(Step::Request& request, Step::Response& response);

  void stepLoop();
  // Every second: does the master still know this node? When a restarted master does not, puts the
  // parameters this node started from back on it (for the respawned node) and shuts down.
  void watchMaster();
  void restoreParameters();
  // Takes one physics step and publishes when it lands on a publishing instant. Caller holds mutex_.
  void stepOnceLocked();
  // Holds a body that became non-finite at its last finite state and logs the one error about it.
  void guardLocked();
  void publishLocked();
  void publishClockLocked();
  // Trail pieces and labels on ~markers at marker instants, built only while someone subscribes.
  void publishMarkersLocked(const ros::Time& stamp);
  // The fixed frames on /tf_static (and <ns>/tf_static).
  void publishStaticTransformsLocked();
  // The fixed frames and the latched ~scene.
  void publishSceneLocked();
  // After the set of bodies or a body's look changed: new placements; the fixed frames and, if it changed,
  // the scene are sent again. Trails go on by body name.
  void rebuildSceneLocked();
  ros::Time stampOf(double t) const;
  void anchorLocked();  // the pace and the wall-clock stamps start from now and the current step
  double wallNow() const;

  ros::NodeHandle node_;
  ros::NodeHandle private_node_;
  XmlRpc::XmlRpcValue start_params_;  // the private namespace as it was at the start
  NodeOptions options_;
  WorldConfig config_;  // the current config of every body (what reconfigure changes)

  std::mutex mutex_;  // guards everything below that the stepping thread touches
  World world_;
  FiniteGuard guard_;
  std::int64_t steps_per_publish_;
  std::int64_t steps_per_markers_;  // a whole number of publishing intervals
  bool markers_watched_ = false;    // whether ~markers had a subscriber at the last publication
  std::int64_t last_published_step_ = -1;
  ros::Time last_clock_;     // the last /clock published (zero: none yet)
  ros::Time last_tf_stamp_;  // the stamp of the last transforms on /tf
  bool paused_ = false;
  StepPacer pacer_;
  std::condition_variable wake_;
  std::unique_ptr<SnapshotBuilder> snapshots_;
  std::unique_ptr<BagRecorder> recorder_;  // the ~bag option: every publication, lossless by construction
  ros::Time stamp_anchor_;    // the wall-clock stamp of simulated time time_anchor_ (without use_sim_time)
  double time_anchor_ = 0.0;  // s
  bool use_sim_time_ = false;

  ros::Publisher marker_publisher_;
  ros::Publisher scene_publisher_;
  ros::Publisher clock_publisher_;
  ros::Publisher namespace_tf_;         // in a namespace: <ns>/tf, a copy of what goes to /tf
  ros::Publisher namespace_tf_static_;  // and <ns>/tf_static
  std::vector<ros::Publisher> state_publishers_;
  std::unique_ptr<std::atomic<int>[]>
      state_subscribers_;  // of each state topic, kept by the publishers' callbacks
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  tf2_ros::StaticTransformBroadcaster static_broadcaster_;
  std::vector<ros::ServiceServer> services_;
  boost::recursive_mutex reconfigure_mutex_;  // the servers' own; updateConfig needs it to be ours
  std::vector<std::unique_ptr<RodServer>> rod_servers_;
  std::vector<std::unique_ptr<RollerServer>> roller_servers_;

  std::atomic<bool> stopping_{false};
  std::atomic<int> exit_status_{0};
  std::thread stepper_;
  std::thread watcher_;
};

}  // namespace rigid_body_sim
