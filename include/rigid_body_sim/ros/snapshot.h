// Everything published at one sample (TF, markers, state messages), shared by sim_node and
// `simulate --bag` so that both publish the same.
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
  tf2_msgs::TFMessage tf;                   // world_frame -> <body>
  visualization_msgs::MarkerArray markers;  // bodies, trails, labels, then the floor and slopes
  std::vector<StateMsg> states;             // in the order of the bodies
};

// Builds snapshots; keeps the bounded trail of every body between calls.
class SnapshotBuilder {
 public:
  // frame_prefix goes in front of every frame but world_frame (the node's option; empty in a bag of
  // simulate).
  SnapshotBuilder(std::string world_frame, std::string frame_prefix, const std::vector<Body>& bodies,
                  std::size_t trail_points = 400);

  std::vector<geometry_msgs::TransformStamped> staticTransforms(const ros::Time& stamp) const;
  visualization_msgs::MarkerArray staticMarkers(const ros::Time& stamp) const;  // floor, slopes
  Snapshot build(double t, const ros::Time& stamp, const std::vector<Body>& bodies);
  // A DELETEALL marker followed by the static markers again; also forgets the trails (for a reset).
  visualization_msgs::MarkerArray restartMarkers(const ros::Time& stamp) {
    return scene_.restartMarkers(stamp);
  }

 private:
  Scene scene_;
};

}  // namespace rigid_body_sim
