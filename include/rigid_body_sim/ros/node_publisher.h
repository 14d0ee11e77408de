// sim_node's topics as a sink of its Session (run/session.h): at every sample /clock, the transforms on /tf
// (and <ns>/tf), ~markers and every ~<body>/state; at every applied command its INFO line, the command on
// ~commands (its index as header.seq) and what follows the bodies; every event on ~events: a spawned body's
// state topic, a deleted one's gone, /tf_static and ~scene rebuilt for a new set of bodies or a new look, the
// trails cleared by a reset. Each message is built only for a topic with a subscriber.
//
// Owned by the stepping thread, which owns the Session: every call but the constructor comes from it. The
// scene sent again for a viewer that joined (a timer on the spinner thread) is handed to it through
// `stepper`. Stamps: simulated time with /use_sim_time, else the wall time of the last anchor() plus the
// simulated time since, never earlier than a stamp already sent.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <ros/ros.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <boost/circular_buffer.hpp>

#include "rigid_body_sim/ros/params.h"
#include "rigid_body_sim/ros/snapshot.h"
#include "rigid_body_sim/run/session.h"
#include "rigid_body_sim/run/task_queue.h"

namespace rigid_body_sim {

class NodePublisher : public SampleSink {
 public:
  // Advertises every topic of `world`'s bodies in `node` (/tf, /clock, <ns>/tf) and `private_node` (the
  // rest); publishes nothing yet.
  NodePublisher(ros::NodeHandle node, ros::NodeHandle private_node, const NodeOptions& options,
                const World& world, bool use_sim_time, TaskQueue& stepper);

  void write(const World& world) override;
  void applied(const WorldCommand& command, std::size_t index, const World& world) override;
  // Each event on ~events, stamped with its instant, and kept for ~get_events.
  void happened(const std::vector<BodyEvent>& events, const World& world) override;

  // The events of the current run (since the start or the last reset or config), at most kKeptEvents, the
  // latest: what ~get_events answers.
  static constexpr std::size_t kKeptEvents = 10000;
  const boost::circular_buffer<BodyEvent>& runEvents() const { return run_events_; }

  void publishConfig(const World& world);  // ~commands' entry 0, the world at the start
  void publishPaused(bool paused);         // ~paused (latched)
  void publishClock(const World& world);   // only forward: /clock never repeats a time
  void publishScene(const World& world);   // /tf_static, then ~scene (latched): when stepping starts
  // The trail up to now and the labels on ~markers off the marker period (the end of a ~step).
  void publishMarkersNow(const World& world);

  // Stamps continue from now at simulated time t (the start of stepping, an unpause).
  void anchor(double t);
  ros::Time stampOf(double t) const;
  // Whether every state topic, ~events and the transforms (/tf or <ns>/tf) have a subscriber.
  bool subscribed() const;
  bool markersSubscribed() const { return markers_.watched(); }

 private:
  // A publisher whose subscribers are counted as they come and go (the count shared with its callbacks: a
  // deleted body's may still run). Publisher::getNumSubscribers looks the topic up among all of the node's
  // publications, and once per body per publication that was most of the node's work with 1000 bodies.
  struct CountedPublisher {
    ros::Publisher publisher;
    std::shared_ptr<std::atomic<int>> subscribers;
    bool watched() const { return subscribers && *subscribers > 0; }
  };
  // `total`, when given, counts the subscribers of every publisher advertised with it as well.
  template <class Message>
  static CountedPublisher advertiseCounted(ros::NodeHandle& node, const std::string& topic,
                                           std::uint32_t queue,
                                           std::shared_ptr<std::atomic<int>> total = nullptr);
  void advertiseState(const Body& body);  // at the end of the list
  void publishMarkers(const World& world, const ros::Time& stamp);
  void publishStaticTransforms(double t);
  // The new placements' fixed frames, then the scene if a marker changed; trails go on by body name.
  void rebuildScene(const World& world);

  ros::NodeHandle node_;
  ros::NodeHandle private_node_;
  bool publish_clock_;
  bool use_sim_time_;
  SnapshotBuilder snapshots_;
  std::int64_t steps_per_markers_;  // a whole number of publishing intervals
  bool markers_watched_ = false;    // whether ~markers had a subscriber at the last publication
  ros::Time last_clock_;            // the last /clock published (zero: none yet)
  ros::Time last_tf_stamp_;         // the stamp of the last transforms on /tf
  ros::Time stamp_anchor_;          // the wall-clock stamp of simulated time time_anchor_
  double time_anchor_ = 0.0;        // s

  ros::Publisher commands_;
  CountedPublisher events_;
  // Full, a new event is copied over the oldest: into its strings' and vectors' room, without allocating.
  boost::circular_buffer<BodyEvent> run_events_{kKeptEvents};
  ros::Publisher paused_;
  CountedPublisher markers_;
  ros::Publisher scene_;
  ros::WallTimer scene_resend_timer_;             // once a second: the scene again for a viewer that joined
  std::atomic<bool> scene_viewer_joined_{false};  // since the last tick
  std::atomic<bool> scene_resend_due_{false};     // a viewer joined before the last tick
  ros::Publisher clock_;
  CountedPublisher tf_;                    // /tf, as tf2_ros::TransformBroadcaster sends it
  CountedPublisher namespace_tf_;          // in a namespace: <ns>/tf, a copy of what goes to /tf
  ros::Publisher namespace_tf_static_;     // and <ns>/tf_static
  std::vector<CountedPublisher> states_;   // in the order of the world's bodies
  std::vector<std::string> state_bodies_;  // their names
  // Of all state topics: none, and a sample looks at no body's publisher.
  std::shared_ptr<std::atomic<int>> state_subscribers_ = std::make_shared<std::atomic<int>>(0);
  tf2_ros::StaticTransformBroadcaster static_broadcaster_;
};

}  // namespace rigid_body_sim
