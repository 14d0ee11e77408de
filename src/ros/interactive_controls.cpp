#include "rigid_body_sim/ros/interactive_controls.h"

#include <cmath>
#include <string>
#include <utility>

#include <ros/console.h>

#include <visualization_msgs/InteractiveMarker.h>
#include <visualization_msgs/InteractiveMarkerControl.h>
#include <visualization_msgs/Marker.h>

namespace rigid_body_sim {

namespace {

using visualization_msgs::InteractiveMarker;
using visualization_msgs::InteractiveMarkerControl;
using visualization_msgs::InteractiveMarkerFeedback;
using visualization_msgs::Marker;

const std::string kVelocitySuffix = "/velocity";
constexpr double kGhostAlpha = 0.45;  // the handles are see-through: the body shows through them
constexpr double kTipSize = 0.1;      // m, the velocity handle's knob
constexpr double kRodGhostThickness = 0.08;

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

std_msgs::ColorRGBA colour(float r, float g, float b) {
  std_msgs::ColorRGBA c;
  c.r = r;
  c.g = g;
  c.b = b;
  c.a = kGhostAlpha;
  return c;
}

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

std::vector<InteractiveMarker> rodMarkers(const BodyConfig& body, const RodConfig& rod) {
  const RodMotion& a = rod.initial;
  InteractiveMarker place = baseMarker(body, body.name, body.name + ": drag to place, ring to turn");
  place.pose.position = point(a.x, a.y);
  place.pose.orientation = aboutZ(a.theta);
  place.scale = static_cast<float>(std::max(0.5, rod.params.length));
  InteractiveMarkerControl move = zAxisControl("move", InteractiveMarkerControl::MOVE_PLANE);
  Marker ghost;
  ghost.type = Marker::CUBE;
  ghost.scale.x = rod.params.length;
  ghost.scale.y = ghost.scale.z = kRodGhostThickness;
  ghost.color = colour(1.0f, 0.9f, 0.2f);
  move.markers.push_back(ghost);
  place.controls = {move, zAxisControl("turn", InteractiveMarkerControl::ROTATE_AXIS)};

  const double dx = a.vx * kVelocityArrowScale, dy = a.vy * kVelocityArrowScale;
  InteractiveMarker throw_ = baseMarker(body, body.name + kVelocitySuffix, "");
  throw_.pose.position = point(a.x + dx, a.y + dy);
  throw_.scale = 0.3f;
  InteractiveMarkerControl aim = zAxisControl("aim", InteractiveMarkerControl::MOVE_PLANE);
  aim.markers = {knob(), velocityArrow(dx, dy)};
  throw_.controls = {aim};
  return {place, throw_};
}

// A body on a slope: a ghost of its shape (`ghost_type`, `ghost_size` across) to slide along the slope at
// its initial position, its centre `half_height` above the slope, and a knob for its initial velocity.
std::vector<InteractiveMarker> slopeMarkers(const BodyConfig& body, double x0, double v0, double half_height,
                                            int ghost_type, double ghost_size) {
  InteractiveMarker place = baseMarker(body, body.name, body.name + ": slide along the slope");
  place.pose.position = point(x0, half_height);
  place.scale = static_cast<float>(std::max(0.5, 4.0 * half_height));
  InteractiveMarkerControl slide = xAxisControl("slide");
  Marker ghost;
  ghost.type = ghost_type;
  ghost.scale.x = ghost.scale.y = ghost.scale.z = ghost_size;
  ghost.color = colour(1.0f, 0.9f, 0.2f);
  slide.markers.push_back(ghost);
  place.controls = {slide};

  const double dx = v0 * kVelocityArrowScale;
  InteractiveMarker throw_ = baseMarker(body, body.name + kVelocitySuffix, "");
  throw_.pose.position = point(x0 + dx, half_height);
  throw_.scale = 0.3f;
  InteractiveMarkerControl aim = xAxisControl("aim");
  aim.markers = {knob(), velocityArrow(dx, 0.0)};
  throw_.controls = {aim};
  return {place, throw_};
}

// Each type's markers, and the keys a drop of them sets: one overload a config type.
std::vector<InteractiveMarker> markersOf(const BodyConfig& body, const RodConfig& rod) {
  return rodMarkers(body, rod);
}
std::vector<InteractiveMarker> markersOf(const BodyConfig& body, const RollerConfig& roller) {
  const double r = roller.params.radius;
  return slopeMarkers(body, roller.initial.x0, roller.initial.v0, r, Marker::SPHERE, 2.4 * r);
}
std::vector<InteractiveMarker> markersOf(const BodyConfig& body, const BlockConfig& block) {
  const double size = block.params.size;
  return slopeMarkers(body, block.initial.x0, block.initial.v0, 0.5 * size, Marker::CUBE, 1.2 * size);
}

// A drop at (x, y) of the body's marker (or, `velocity`, of its knob): a rod's place and angle, or its
// velocity; a body on a slope's position along it, or its velocity.
std::map<std::string, double> droppedKeys(const RodConfig& rod, bool velocity, double x, double y,
                                          const geometry_msgs::Pose& pose) {
  const RodMotion& a = rod.initial;
  if (velocity) return {{"vx0", (x - a.x) / kVelocityArrowScale}, {"vy0", (y - a.y) / kVelocityArrowScale}};
  return {{"x0", x}, {"y0", y}, {"theta0", angleAboutZ(pose.orientation)}};
}
std::map<std::string, double> slopeDrop(double x0, bool velocity, double x) {
  if (velocity) return {{"v0", (x - x0) / kVelocityArrowScale}};
  return {{"x0", x}};
}
std::map<std::string, double> droppedKeys(const RollerConfig& roller, bool velocity, double x, double,
                                          const geometry_msgs::Pose&) {
  return slopeDrop(roller.initial.x0, velocity, x);
}
std::map<std::string, double> droppedKeys(const BlockConfig& block, bool velocity, double x, double,
                                          const geometry_msgs::Pose&) {
  return slopeDrop(block.initial.x0, velocity, x);
}

// Whether the body's marker turns (its drop reads an orientation): a rod's only.
bool turns(const RodConfig&) { return true; }
bool turns(const RollerConfig&) { return false; }
bool turns(const BlockConfig&) { return false; }

}  // namespace

InteractiveControls::InteractiveControls(const std::string& server_ns, std::string frame_prefix,
                                         DropHandler on_drop)
    : server_(server_ns), frame_prefix_(std::move(frame_prefix)), on_drop_(std::move(on_drop)) {}

std::map<std::string, double> InteractiveControls::dropped(const BodyConfig& body, const std::string& marker,
                                                           const geometry_msgs::Pose& pose) {
  const bool velocity = marker == body.name + kVelocitySuffix;
  const double x = pose.position.x, y = pose.position.y;
  return std::visit([&](const auto& config) { return droppedKeys(config, velocity, x, y, pose); },
                    body.config);
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
  auto markers = std::visit([&](const auto& config) { return markersOf(body, config); }, body.config);
  for (auto& marker : markers) {
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
  const bool reads_orientation =
      std::visit([](const auto& config) { return turns(config); }, body.config) && marker == body.name;
  const std::string fault = poseFault(reads_orientation, feedback->pose);
  if (!fault.empty()) ROS_WARN_STREAM("drop of marker '" << marker << "' refused: " << fault);
  std::string why;
  if (!fault.empty() || !on_drop_(name, dropped(body, marker, feedback->pose), &why)) {
    insert(body);
    server_.applyChanges();
  }
}

}  // namespace rigid_body_sim
