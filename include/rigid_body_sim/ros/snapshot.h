// Everything published at one sample (TF, state messages) and the scene's markers, shared by sim_node
// and `simulate --bag` so that both publish the same.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <geometry_msgs/TransformStamped.h>
#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/MarkerArray.h>

#include "rigid_body_sim/ros/messages.h"
#include "rigid_body_sim/ros/scene.h"

namespace rigid_body_sim {

struct Snapshot {
  tf2_msgs::TFMessage tf;  // world_frame -> <body> (and -> <body>_ground after a rod on an unbounded floor)
  std::vector<StateMsg> states;  // in the order of the bodies
};

// Builds snapshots; owns the scene (placements, markers, trails).
class SnapshotBuilder {
 public:
  // frame_prefix goes in front of every frame but world_frame (the node's option; empty in a bag of
  // simulate).
  SnapshotBuilder(std::string world_frame, std::string frame_prefix, const std::vector<Body>& bodies,
                  MarkerOptions trail = {});

  std::vector<geometry_msgs::TransformStamped> staticTransforms(const ros::Time& stamp) const;
  Snapshot build(double t, const ros::Time& stamp, const std::vector<Body>& bodies) const;
  // What build() gives for body i alone: for a publisher that builds only what someone subscribes to.
  geometry_msgs::TransformStamped transform(std::size_t i, const ros::Time& stamp, const Body& body) const;
  // Body i's transform and, for a rod on an unbounded floor, its ground frame's, appended to `tf`.
  void appendTransforms(std::size_t i, const ros::Time& stamp, const Body& body,
                        tf2_msgs::TFMessage& tf) const;
  StateMsg state(std::size_t i, double t, const ros::Time& stamp, const Body& body) const;
  Scene& scene() { return scene_; }
  const Scene& scene() const { return scene_; }

 private:
  Scene scene_;
};

}  // namespace rigid_body_sim
