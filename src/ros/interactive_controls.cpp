#include "rigid_body_sim/ros/interactive_controls.h"

#include <cmath>
#include <string>
#include <utility>

#include <ros/console.h>

#include <visualization_msgs/InteractiveMarker.h>
#include <visualization_msgs/InteractiveMarkerControl.h>
#include <visualization_msgs/Marker.h>

#include "rigid_body_sim/core/names.h"
#include "rigid_body_sim/ros/body_types_ros.h"

namespace rigid_body_sim {

namespace {

using visualization_msgs::InteractiveMarker;
using visualization_msgs::InteractiveMarkerControl;
using visualization_msgs::InteractiveMarkerFeedback;
using visualization_msgs::Marker;

const std::string kVelocitySuffix = "/velocity";
constexpr double kGhostAlpha = 0.45;  // the handles are see-through: the body shows through them
constexpr double kTipSize = 0.1;      // m, the velocity handle's knob

geometry_msgs::Quaternion aboutZ(double angle) {
  geometry_msgs::Quaternion q;
  q.z = std::sin(angle / 2);
  q.w = std::cos(angle / 2);
  return q;
}

// The angle about z of a rotation (rviz may add rounding off the z axis: its projection on the plane).
double angleAboutZ(const geometry_msgs::Quaternion& q) {
  return std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
}

// Why a dropped pose cannot be taken, or empty: a position that is not finite, or (for a rod's place, whose
// turn is read from it) an orientation that is no rotation, such as the zero quaternion.
std::string poseFault(bool reads_orientation, const geometry_msgs::Pose& pose) {
  const auto& p = pose.position;
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return "its position is not finite";
  const auto& q = pose.orientation;
  const double norm2 = q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w;
  if (reads_orientation && !(std::abs(norm2 - 1.0) < 1e-3)) {
    return "its orientation (" + formatNumber(q.x) + ", " + formatNumber(q.y) + ", " + formatNumber(q.z) +
           ", " + formatNumber(q.w) + ") is no rotation (a unit quaternion)";
  }
  return "";
}

geometry_msgs::Point point(double x, double y) {
  geometry_msgs::Point p;
  p.x = x;
  p.y = y;
  return p;
}

// The handles' colours: see-through.
std_msgs::ColorRGBA colour(float r, float g, float b) { return rgba(r, g, b, kGhostAlpha); }

// A control whose axis (rviz: the control's x axis) is the frame's z: planar moves and turns about z.
InteractiveMarkerControl zAxisControl(const std::string& name, std::uint8_t mode) {
  InteractiveMarkerControl control;
  control.name = name;
  control.interaction_mode = mode;
  control.orientation.w = std::sqrt(0.5);
  control.orientation.y = std::sqrt(0.5);
  return control;
}

// A control along the frame's x axis (a roller slides down its slope).
InteractiveMarkerControl xAxisControl(const std::string& name) {
  InteractiveMarkerControl control;
  control.name = name;
  control.interaction_mode = InteractiveMarkerControl::MOVE_AXIS;
  control.orientation.w = 1.0;
  return control;
}

// The arrow from the body's initial position to the handle (in the handle's frame: it ends at the origin).
Marker velocityArrow(double dx, double dy) {
  Marker arrow;
  arrow.type = Marker::ARROW;
  arrow.points = {point(-dx, -dy), point(0, 0)};
  arrow.scale.x = 0.03;  // shaft diameter
  arrow.scale.y = 0.07;  // head diameter
  arrow.scale.z = 0.1;   // head length
  arrow.color = colour(1.0f, 0.55f, 0.0f);
  arrow.color.a = 0.9f;
  return arrow;
}

Marker knob() {
  Marker tip;
  tip.type = Marker::SPHERE;
  tip.scale.x = tip.scale.y = tip.scale.z = kTipSize;
  tip.color = colour(1.0f, 0.55f, 0.0f);
  tip.color.a = 0.9f;
  return tip;
}

InteractiveMarker baseMarker(const BodyConfig& body, const std::string& name,
                             const std::string& description) {
  InteractiveMarker marker;
  marker.header.frame_id = fixedFrameOf(body);
  marker.name = name;
  marker.description = description;
  marker.pose.orientation.w = 1.0;
  return marker;
}

BodyHandles handlesOf(const BodyConfig& body) {
  return std::visit(
      [](const auto& config) { return RosBodyType<TypeOfConfig<decltype(config)>>::handles(config); },
      body.config);
}

// The ghost to drag: along the slope's x for a body on a slope, in its plane and turned for one that turns.
InteractiveMarker placeMarker(const BodyConfig& body, const BodyHandles& handles) {
  const bool turns = handles.angle_key != nullptr;
  InteractiveMarker place = baseMarker(
      body, body.name, body.name + (turns ? ": drag to place, ring to turn" : ": slide along the slope"));
  place.pose.position = point(handles.position.x(), handles.position.y());
  place.pose.orientation = aboutZ(handles.angle);
  place.scale = static_cast<float>(handles.size);
  InteractiveMarkerControl move =
      handles.y_key ? zAxisControl("move", InteractiveMarkerControl::MOVE_PLANE) : xAxisControl("slide");
  Marker ghost;
  ghost.type = handles.ghost.type;
  ghost.scale.x = handles.ghost.scale.x();
  ghost.scale.y = handles.ghost.scale.y();
  ghost.scale.z = handles.ghost.scale.z();
  ghost.color = colour(1.0f, 0.9f, 0.2f);
  move.markers.push_back(ghost);
  place.controls = {move};
  if (turns) place.controls.push_back(zAxisControl("turn", InteractiveMarkerControl::ROTATE_AXIS));
  return place;
}

// The knob at the tip of the initial velocity's arrow.
InteractiveMarker throwMarker(const BodyConfig& body, const BodyHandles& handles) {
  const Eigen::Vector2d arrow = handles.velocity * kVelocityArrowScale;
  InteractiveMarker throw_ = baseMarker(body, body.name + kVelocitySuffix, "");
  throw_.pose.position = point(handles.position.x() + arrow.x(), handles.position.y() + arrow.y());
  throw_.scale = 0.3f;
  InteractiveMarkerControl aim =
      handles.vy_key ? zAxisControl("aim", InteractiveMarkerControl::MOVE_PLANE) : xAxisControl("aim");
  aim.markers = {knob(), velocityArrow(arrow.x(), arrow.y())};
  throw_.controls = {aim};
  return throw_;
}

}  // namespace

InteractiveControls::InteractiveControls(const std::string& server_ns, std::string frame_prefix,
                                         DropHandler on_drop)
    : server_(server_ns), frame_prefix_(std::move(frame_prefix)), on_drop_(std::move(on_drop)) {}

// A drop at (x, y) of the body's ghost: its position (and angle); of its knob: its velocity.
std::map<std::string, double> InteractiveControls::dropped(const BodyConfig& body, const std::string& marker,
                                                           const geometry_msgs::Pose& pose) {
  const BodyHandles handles = handlesOf(body);
  const double x = pose.position.x, y = pose.position.y;
  std::map<std::string, double> keys;
  if (marker == body.name + kVelocitySuffix) {
    keys[handles.vx_key] = (x - handles.position.x()) / kVelocityArrowScale;
    if (handles.vy_key) keys[handles.vy_key] = (y - handles.position.y()) / kVelocityArrowScale;
    return keys;
  }
  keys[handles.x_key] = x;
  if (handles.y_key) keys[handles.y_key] = y;
  if (handles.angle_key) keys[handles.angle_key] = angleAboutZ(pose.orientation);
  return keys;
}

void InteractiveControls::show(const WorldConfig& config) {
  std::map<std::string, BodyConfig> now;
  for (const BodyConfig& body : config.bodies) {
    now.emplace(body.name, body);
    insert(body);
  }
  for (const auto& [name, body] : bodies_) {
    if (!now.count(name)) {
      server_.erase(name);
      server_.erase(name + kVelocitySuffix);
    }
  }
  bodies_ = std::move(now);
  server_.applyChanges();
}

void InteractiveControls::insert(const BodyConfig& body) {
  const BodyHandles handles = handlesOf(body);
  for (auto marker : {placeMarker(body, handles), throwMarker(body, handles)}) {
    marker.header.frame_id = frame_prefix_ + fixedFrameOf(body);
    server_.insert(
        marker, [this](const auto& feedback) { onFeedback(feedback); }, InteractiveMarkerFeedback::MOUSE_UP);
  }
}

// On a drop the handler applies the initial conditions and, if they run, shows every body anew through
// show(); a refused drop puts both markers of the body back where its initial conditions are.
void InteractiveControls::onFeedback(const visualization_msgs::InteractiveMarkerFeedbackConstPtr& feedback) {
  const std::string& marker = feedback->marker_name;
  const std::string name = marker.substr(0, marker.find('/'));
  const auto found = bodies_.find(name);
  if (found == bodies_.end()) {
    ROS_WARN_STREAM("drop of marker '" << marker << "' ignored: there is no body '" << name
                                       << "' (deleted?)");
    return;
  }
  const BodyConfig body = found->second;  // the handler may replace bodies_ (through show)
  const bool reads_orientation = handlesOf(body).angle_key != nullptr && marker == body.name;
  const std::string fault = poseFault(reads_orientation, feedback->pose);
  if (!fault.empty()) ROS_WARN_STREAM("drop of marker '" << marker << "' refused: " << fault);
  std::string why;
  if (!fault.empty() || !on_drop_(name, dropped(body, marker, feedback->pose), &why)) {
    insert(body);
    server_.applyChanges();
  }
}

}  // namespace rigid_body_sim
