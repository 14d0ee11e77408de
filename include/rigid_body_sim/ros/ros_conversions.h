// Core state -> ROS messages: TF, markers and state messages, shared by sim_node and `simulate --bag`.
//
// Placement in the world (REP 103: x forward, z up; all in world_frame):
// - every body has a fixed 2-D frame in which its CSV coordinates are measured, published on /tf_static:
//   a rod's `<body>_floor` (x along the world x, y up = world z, on the floor z = 0) and a roller's
//   `<body>_slope` (x down the slope, y normal to it, origin at the top of the slope);
// - rods stand in the plane world y = -1.5 i (i-th rod), rollers in lanes world y = 1 + 0.5 j (wider for
//   large radii): side by side, never overlapping; every slope ends on the floor at its lower end.
#pragma once

#include <cstddef>
#include <deque>
#include <string>
#include <variant>
#include <vector>

#include <geometry_msgs/TransformStamped.h>
#include <ros/time.h>
#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/MarkerArray.h>
#include <Eigen/Geometry>

#include "rigid_body_sim/RodState.h"
#include "rigid_body_sim/RollerState.h"
#include "rigid_body_sim/core/world.h"

namespace rigid_body_sim {

// Simulated time as a ROS stamp: t plus 1 ns, so that the t = 0 sample is a valid, non-zero time.
ros::Time simStamp(double t);

// The fixed frame of a body (its floor or slope) and where it sits in the world.
struct BodyPlacement {
  std::string frame;  // <body>_floor or <body>_slope
  Eigen::Isometry3d world_from_frame;
  double slope_length = 0.0;  // m; 0 for a rod's floor
};
std::vector<BodyPlacement> placeBodies(const std::vector<Body>& bodies);

// Pose of the body (its centre, rotated by its angle about the frame's z) in its fixed frame.
Eigen::Isometry3d frameFromBody(const Body& body);

RodState toRodStateMsg(double t, const Rod& rod);
RollerState toRollerStateMsg(double t, const Roller& roller);
using StateMsg = std::variant<RodState, RollerState>;

// Everything published at one sample time.
struct Snapshot {
  tf2_msgs::TFMessage tf;                   // world_frame -> <body>
  visualization_msgs::MarkerArray markers;  // bodies, trails, labels (floor and slopes: staticMarkers)
  std::vector<StateMsg> states;             // in the order of the bodies
};

// Builds snapshots; keeps the bounded trail of every body between calls.
class SnapshotBuilder {
 public:
  SnapshotBuilder(std::string world_frame, const std::vector<Body>& bodies, std::size_t trail_points = 400);

  std::vector<geometry_msgs::TransformStamped> staticTransforms(const ros::Time& stamp) const;
  visualization_msgs::MarkerArray staticMarkers(const ros::Time& stamp) const;  // floor, slopes
  Snapshot build(double t, const ros::Time& stamp, const std::vector<Body>& bodies);
  // A DELETEALL marker followed by the static markers again; also forgets the trails (for a reset).
  visualization_msgs::MarkerArray restartMarkers(const ros::Time& stamp);

 private:
  std::string world_frame_;
  std::vector<BodyPlacement> placements_;
  std::size_t trail_points_;
  std::vector<std::deque<Eigen::Vector3d>> trails_;
};

}  // namespace rigid_body_sim
