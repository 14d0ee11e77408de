// Where every body sits in the world and how it looks in rviz: the fixed frames and the markers.
//
// Placement in the world (REP 103: x forward, z up; all in world_frame):
// - every body has a fixed 2-D frame in which its CSV coordinates are measured, published on /tf_static:
//   a rod's `<body>_floor` (x along the world x, y up = world z, on the floor z = 0) and a roller's
//   `<body>_slope` (x down the slope, y normal to it, origin at the top of the slope);
// - rods stand in the plane world y = -1.5 i (i-th rod), rollers in lanes world y = 1 + 0.5 j (wider for
//   large radii): side by side, never overlapping; every slope ends on the floor at its lower end.
// Every frame but world_frame carries a prefix (the node's frame_prefix, empty by default), so that two
// instances publish distinct frames on one /tf.
#pragma once

#include <cstddef>
#include <deque>
#include <string>
#include <vector>

#include <ros/time.h>
#include <visualization_msgs/MarkerArray.h>
#include <Eigen/Geometry>

#include "rigid_body_sim/core/world.h"

namespace rigid_body_sim {

// The fixed frame of a body (its floor or slope) and where it sits in the world.
struct BodyPlacement {
  std::string frame;  // <body>_floor or <body>_slope
  Eigen::Isometry3d world_from_frame;
  double slope_length = 0.0;  // m; 0 for a rod's floor
  double floor_length = 0.0;  // m of a rod's bounded floor; 0 for an unbounded floor and for a slope
};
std::vector<BodyPlacement> placeBodies(const std::vector<Body>& bodies, const std::string& frame_prefix = "");

// Pose of the body (its centre, rotated by its angle about the frame's z) in its fixed frame.
Eigen::Isometry3d frameFromBody(const Body& body);

// The markers of a world: fixed scenery (floor, slopes) and, at every sample, each body's shape, a spoke
// that turns with it, its bounded trail and a label with its mode and energy.
class Scene {
 public:
  Scene(std::string world_frame, std::string frame_prefix, const std::vector<Body>& bodies,
        std::size_t trail_points = 400);

  const std::string& worldFrame() const { return world_frame_; }
  std::string bodyFrame(const Body& body) const { return frame_prefix_ + body.name; }
  const std::vector<BodyPlacement>& placements() const { return placements_; }

  visualization_msgs::MarkerArray fixedMarkers(const ros::Time& stamp) const;  // floors, slopes
  // Appends the markers of body `index`, whose centre is at world_from_body, and extends its trail.
  void addBodyMarkers(std::size_t index, const Body& body, const Eigen::Isometry3d& world_from_body,
                      const ros::Time& stamp, visualization_msgs::MarkerArray& markers);
  // A DELETEALL marker followed by the fixed markers again; also forgets the trails (for a reset).
  visualization_msgs::MarkerArray restartMarkers(const ros::Time& stamp);

 private:
  std::string world_frame_;
  std::string frame_prefix_;
  std::vector<BodyPlacement> placements_;
  std::size_t trail_points_;
  std::vector<std::deque<Eigen::Vector3d>> trails_;
};

}  // namespace rigid_body_sim
