#include "rigid_body_sim/ros/types/roller_ros.h"

#include <algorithm>
#include <cmath>

#include <visualization_msgs/Marker.h>

#include "rigid_body_sim/core/constants.h"

namespace rigid_body_sim {

namespace {

constexpr double kCylinderLength = 0.8;  // of a cylinder's diameter
constexpr double kRingWidth = 0.15;      // of a ring's radius
constexpr int kRingSegments = 48;
constexpr double kGhostAcross = 2.4;  // its interactive ghost: radii across

std_msgs::ColorRGBA colourOf(Shape shape) {
  switch (shape) {
    case Shape::Sphere: return rgba(0.9f, 0.1f, 0.1f);
    case Shape::Cylinder: return rgba(0.1f, 0.8f, 0.1f);
    case Shape::Ring: return rgba(1.0f, 0.6f, 0.0f);
    case Shape::SphericalShell: return rgba(0.7f, 0.1f, 0.9f);
    case Shape::Custom: return rgba(0.6f, 0.6f, 0.6f);
  }
  return rgba(1, 1, 1);
}

}  // namespace

template <>
BodyLook RosBodyType<RollerType>::look(const Roller& roller) {
  const RollerParams& p = roller.params();
  BodyLook look;
  look.colour = colourOf(p.shape);
  look.incline = Incline{p.incline_angle, p.incline_length};
  look.radius = look.reach = p.radius;
  look.pose.translate(Eigen::Vector3d(roller.state().x, p.radius, 0.0));  // on the slope
  look.pose.rotate(Eigen::AngleAxisd(roller.state().theta, Eigen::Vector3d::UnitZ()));
  look.spoke = true;
  look.critical_tangent = criticalTangent(p.mu_s, p.inertia_factor);
  return look;
}

template <>
BodyShape RosBodyType<RollerType>::shape(const Roller& roller) {
  const RollerParams& p = roller.params();
  const double d = 2.0 * p.radius;
  BodyShape shape;
  if (p.shape == Shape::Ring) {
    shape.type = visualization_msgs::Marker::LINE_STRIP;
    shape.scale = {kRingWidth * p.radius, 0.0, 0.0};
    for (int i = 0; i <= kRingSegments; ++i) {
      const double a = 2.0 * kPi * i / kRingSegments;
      shape.points.emplace_back(p.radius * std::cos(a), p.radius * std::sin(a), 0.0);
    }
    return shape;
  }
  const bool cylinder = p.shape == Shape::Cylinder;
  shape.type = cylinder ? visualization_msgs::Marker::CYLINDER : visualization_msgs::Marker::SPHERE;
  shape.scale = {d, d, cylinder ? kCylinderLength * d : d};
  return shape;
}

template <>
BodyHandles RosBodyType<RollerType>::handles(const RollerConfig& roller) {
  const double r = roller.params.radius;
  BodyHandles handles;
  handles.position = {roller.initial.x0, r};
  handles.velocity = {roller.initial.v0, 0.0};
  handles.size = std::max(0.5, 4.0 * r);
  handles.ghost.type = visualization_msgs::Marker::SPHERE;
  handles.ghost.scale = Eigen::Vector3d::Constant(kGhostAcross * r);
  handles.x_key = "x0";
  handles.vx_key = "v0";
  return handles;
}

}  // namespace rigid_body_sim
