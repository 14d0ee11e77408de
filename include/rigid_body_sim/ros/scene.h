// Where every body sits in the world and how it looks in rviz: the fixed frames and the markers.
//
// Placement in the world (REP 103: x forward, z up; all in world_frame):
// - every body has a fixed 2-D frame in which its CSV coordinates are measured, published on /tf_static:
//   a rod's `<body>_floor` (x along the world x, y up = world z, on the floor z = 0) and a roller's
//   `<body>_slope` (x down the slope, y normal to it, origin at the top of the slope);
// - rods stand in the plane world y = -1.5 i (i-th rod), rollers in lanes from world y = 1, 0.5 apart (wider
//   for large radii), every slope's lower end on the floor: side by side, never overlapping. The lanes go by
//   steepness, the shallowest nearest (the smallest y; equal angles in the bodies' order), and a steeper
//   slope ends where the nearer ones end, 0.8 m further than a shallower one; the first top is at x = 0.
//   Seen from the side a further slope then stands above every nearer one wherever both are, so that in
//   a view from the front no slope crosses another's lane, whatever their angles. One this would move
//   more than 7 m along keeps its top at x = 0 and lies further back instead;
// - a rod on an unbounded floor has a frame `<body>_ground` (on /tf, with the body's): the world's axes,
//   its origin at the rod's world x rounded to whole metres (rviz's grid cells), y = z = 0. Its floor and
//   rviz's Grid are drawn in it: under the rod wherever it goes, and still in the world's grid;
// - a label floats above the highest point its body can reach (a rod's half length), higher in each
//   further lane, so that the labels of rollers racing side by side do not cover one another in a view
//   from the side; a roller's runs downhill from above it but stays over the slopes' stretch of x, just in
//   front of its slope.
// Every frame but world_frame carries a prefix (the node's frame_prefix, empty by default), so that two
// instances publish distinct frames on one /tf.
//
// The markers come in two streams, so that their cost follows what changes:
// - the scene (latched): DELETEALL, the floor, every slope and each body's shape and spoke, drawn
//   frame_locked in the body's own TF frame, so that TF moves them. Built anew by rebuild() and sent
//   again only when it differs;
// - the changes (at the marker rate): for every body the piece of its trail added since the last
//   changes() (a short LINE_STRIP whose id comes from a ring, so that the oldest piece is overwritten once
//   the trail is `trail_seconds` long) and its label (mode, and energy or critical angle).
#pragma once

#include <cstddef>
#include <map>
#include <optional>
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
  std::string ground_frame;   // <body>_ground of a rod on an unbounded floor; empty for any other body
};
std::vector<BodyPlacement> placeBodies(const std::vector<Body>& bodies, const std::string& frame_prefix = "");
// Each roller's lane, in the order of the rollers among the bodies.
struct Lane {
  double top_x = 0.0;    // world x of its slope's top
  double y = 0.0;        // world y
  std::size_t rank = 0;  // 0 for the nearest lane (the smallest y)
};
std::vector<Lane> placeLanes(const std::vector<Body>& bodies);
// Where a ground frame is for the body at its current place (the placement must have one).
Eigen::Isometry3d worldFromGround(const BodyPlacement& placement, const Body& body);

// Pose of the body (its centre, rotated by its angle about the frame's z) in its fixed frame.
Eigen::Isometry3d frameFromBody(const Body& body);

// How long the trails are, how often their pieces are sent, what the labels say.
struct MarkerOptions {
  double seconds = 8.0;          // simulated seconds of trail; 0 = no trails
  double pieces_rate = 10.0;     // Hz: how often changes() is called (the marker rate)
  bool critical_angles = false;  // a roller's label gives its critical angle, not its energy (a lesson)
  // Pieces a trail is made of: the ring of ids each body's pieces cycle through.
  int ring() const;
};

class Scene {
 public:
  Scene(std::string world_frame, std::string frame_prefix, const std::vector<Body>& bodies,
        MarkerOptions trail = {});

  const std::string& worldFrame() const { return world_frame_; }
  std::string bodyFrame(const Body& body) const { return frame_prefix_ + body.name; }
  const std::vector<BodyPlacement>& placements() const { return placements_; }

  // For a new set of bodies or a new look (a spawn, a delete, a reconfigured slope or shape): new
  // placements and scene. Trails are kept by body name; a removed body's trail and label are deleted by
  // the next changes(), and so is the trail of a body whose fixed frame moved (a new slope: its path so far
  // would float where the old slope was). Returns whether the scene's markers changed (then send
  // sceneMarkers() again).
  bool rebuild(const std::vector<Body>& bodies);

  // The latched scene: DELETEALL first, then the floor, the slopes and every body's shape and spoke.
  // Stamped 0 (use the latest transform), so that a viewer that joins late can draw it at once.
  const visualization_msgs::MarkerArray& sceneMarkers() const { return scene_; }

  // Adds every body's current position to its trail (at every publication, while someone watches).
  void sample(const std::vector<Body>& bodies);
  // The trail pieces since the last call (each starts at the previous piece's last point, so that the
  // line has no gap) and every body's label; deletions of removed bodies' markers.
  visualization_msgs::MarkerArray changes(const ros::Time& stamp, const std::vector<Body>& bodies);
  // Forgets the trails (a reset, or nobody watches): the next pieces start afresh.
  void clearTrails();
  // A DELETEALL for the changes' stream: removes every trail and label from a viewer.
  visualization_msgs::MarkerArray clearMarkers(const ros::Time& stamp) const;

 private:
  struct Trail {
    int slot = 0;                          // the body's place in the id space, kept while it exists
    std::vector<Eigen::Vector3d> pending;  // points since the last piece
    std::optional<Eigen::Vector3d> last;   // the last point sent, where the next piece starts
    long long pieces = 0;                  // pieces sent: the next one's place in the ring
  };
  Trail& trailOf(const std::string& body);

  std::string world_frame_;
  std::string frame_prefix_;
  MarkerOptions marker_options_;
  std::vector<BodyPlacement> placements_;
  visualization_msgs::MarkerArray scene_;
  std::map<std::string, Trail> trails_;
  std::vector<int> removed_slots_;           // of bodies gone since the last changes()
  std::vector<int> moved_slots_;             // of bodies whose fixed frame moved: their trails go
  std::vector<Eigen::Vector3d> board_ends_;  // by placement: where a roller's board ends (its right, centre)
  int next_slot_ = 0;
};

}  // namespace rigid_body_sim
