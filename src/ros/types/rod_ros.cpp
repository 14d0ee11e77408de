#include "rigid_body_sim/ros/types/rod_ros.h"

#include <cmath>

#include <visualization_msgs/Marker.h>

#include "rigid_body_sim/core/constants.h"

namespace rigid_body_sim {

namespace {

constexpr double kThickness = 0.05;       // m: the rod drawn, and its half width across its plane
constexpr double kGhostThickness = 0.08;  // m: its interactive ghost, a little wider than the rod

}  // namespace

template <>
BodyLook RosBodyType<RodType>::look(const Rod& rod) {
  BodyLook look;
  look.colour = rgba(0.1f, 0.3f, 0.9f);
  look.floor_length = rod.params().floor_length;
  look.radius = kThickness;
  look.reach = 0.5 * rod.params().length;
  look.pose.translate(Eigen::Vector3d(rod.state().x, rod.state().y, 0.0));
  look.pose.rotate(Eigen::AngleAxisd(rod.state().theta, Eigen::Vector3d::UnitZ()));
  return look;
}

template <>
BodyShape RosBodyType<RodType>::shape(const Rod& rod) {
  BodyShape shape;
  shape.type = visualization_msgs::Marker::CYLINDER;
  // A marker cylinder lies along its z; the rod lies along its frame's x.
  shape.orientation = Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitY());
  shape.scale = {kThickness, kThickness, rod.params().length};
  return shape;
}

template <>
BodyHandles RosBodyType<RodType>::handles(const RodConfig& rod) {
  const RodMotion& a = rod.initial;
  BodyHandles handles;
  handles.position = {a.x, a.y};
  handles.angle = a.theta;
  handles.velocity = {a.vx, a.vy};
  handles.size = std::max(0.5, rod.params.length);
  handles.ghost.type = visualization_msgs::Marker::CUBE;
  handles.ghost.scale = {rod.params.length, kGhostThickness, kGhostThickness};
  handles.x_key = "x0";
  handles.y_key = "y0";
  handles.angle_key = "theta0";
  handles.vx_key = "vx0";
  handles.vy_key = "vy0";
  return handles;
}

}  // namespace rigid_body_sim
