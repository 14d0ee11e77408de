// Interactive markers that place and throw the bodies by hand in rviz: a server at ~interactive with, per
// body, a marker named after it (its initial pose, in the body's fixed frame) and one named
// "<body>/velocity" (the tip of its initial velocity arrow). On release (MOUSE_UP) the pose dropped
// becomes initial conditions, handed to the node's drop handler, which validates and applies them like a
// reconfigure; a refused drop puts the marker back.
//   rod, in <body>_floor:      drag in (x, y), turn about z: x0, y0, theta0; arrow tip: vx0, vy0
//   roller, in <body>_slope:   slide along x: x0; arrow tip along x: v0
// The arrow's tip lies at the body's initial position plus velocity × kVelocityArrowScale.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <interactive_markers/interactive_marker_server.h>
#include <ros/ros.h>
#include <visualization_msgs/InteractiveMarkerFeedback.h>

#include "rigid_body_sim/core/parameters.h"

namespace rigid_body_sim {

// Metres of arrow per m/s of initial velocity (seconds): 2 m/s is half a metre of arrow.
inline constexpr double kVelocityArrowScale = 0.25;

class InteractiveControls {
 public:
  // Applies initial conditions dropped for a body (keys as in the config: x0, y0, theta0, vx0, vy0 of a
  // rod; x0, v0 of a roller). True if they now run; false with the reason in *why if refused.
  using DropHandler = std::function<bool(const std::string& body,
                                         const std::map<std::string, double>& initial, std::string* why)>;

  // Serves under `server_ns` (the node's private namespace + "/interactive"); the markers are in the bodies'
  // fixed frames with `frame_prefix` in front (the node's frame_prefix).
  InteractiveControls(const std::string& server_ns, std::string frame_prefix, DropHandler on_drop);

  // Shows every body of `config` at its initial conditions; removes the markers of bodies it no longer has.
  void show(const WorldConfig& config);

  // The initial keys a marker of `body` drops, from a pose in the body's fixed frame (pure: tested alone).
  static std::map<std::string, double> dropped(const BodyConfig& body, const std::string& marker,
                                               const geometry_msgs::Pose& pose);

 private:
  void onFeedback(const visualization_msgs::InteractiveMarkerFeedbackConstPtr& feedback);
  void insert(const BodyConfig& body);

  interactive_markers::InteractiveMarkerServer server_;
  std::string frame_prefix_;
  DropHandler on_drop_;
  std::map<std::string, BodyConfig> bodies_;  // what is shown, by body name
};

}  // namespace rigid_body_sim
