#include "rigid_body_sim/ros/types/block_ros.h"

#include <algorithm>

#include <visualization_msgs/Marker.h>

namespace rigid_body_sim {

namespace {

constexpr double kGhostAcross = 1.2;  // its interactive ghost: edges across

}  // namespace

template <>
BodyLook RosBodyType<BlockType>::look(const Block& block) {
  const BlockParams& p = block.params();
  BodyLook look;
  look.colour = rgba(0.0f, 0.65f, 0.7f);
  look.incline = Incline{p.incline_angle, p.incline_length};
  look.radius = look.reach = 0.5 * p.size;
  look.pose.translate(Eigen::Vector3d(block.state().x, 0.5 * p.size, 0.0));  // on the slope, never turned
  look.critical_tangent = p.mu_s;
  return look;
}

template <>
BodyShape RosBodyType<BlockType>::shape(const Block& block) {
  BodyShape shape;
  shape.type = visualization_msgs::Marker::CUBE;
  shape.scale = Eigen::Vector3d::Constant(block.params().size);
  return shape;
}

template <>
BodyHandles RosBodyType<BlockType>::handles(const BlockConfig& block) {
  const double size = block.params.size;
  BodyHandles handles;
  handles.position = {block.initial.x0, 0.5 * size};
  handles.velocity = {block.initial.v0, 0.0};
  handles.size = std::max(0.5, 2.0 * size);
  handles.ghost.type = visualization_msgs::Marker::CUBE;
  handles.ghost.scale = Eigen::Vector3d::Constant(kGhostAcross * size);
  handles.x_key = "x0";
  handles.vx_key = "v0";
  return handles;
}

}  // namespace rigid_body_sim
