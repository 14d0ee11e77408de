// Core state -> ROS messages: the state messages, events, stamps, and Eigen poses as geometry messages.
#pragma once

#include <string>
#include <type_traits>
#include <variant>

#include <geometry_msgs/Point.h>
#include <geometry_msgs/Pose.h>
#include <geometry_msgs/TransformStamped.h>
#include <ros/time.h>
#include <Eigen/Geometry>

#include "rigid_body_sim/Event.h"
#include "rigid_body_sim/core/world.h"
#include "rigid_body_sim/ros/body_types_ros.h"

namespace rigid_body_sim {

// Simulated time as a ROS stamp: t plus 1 ns, so that the t = 0 sample is a valid, non-zero time.
ros::Time simStamp(double t);

// The state messages carry the fields of core/state_fields.h (test_messages checks the definitions); the
// header is left to the caller.
template <class Model, class = std::enable_if_t<!std::is_same_v<Model, Body>>>
auto toStateMsg(double t, const Model& model) {
  return RosBodyType<TypeOfModel<Model>>::state(t, model);
}
StateMsg toStateMsg(double t, const Body& body);

// An event as published on ~events and recorded (rigid_body_sim/Event), stamped `stamp` (its instant).
rigid_body_sim::Event toEventMsg(const BodyEvent& event, const ros::Time& stamp);

geometry_msgs::Point toPoint(const Eigen::Vector3d& point);
geometry_msgs::Pose toPose(const Eigen::Isometry3d& transform);
geometry_msgs::TransformStamped toTransform(const Eigen::Isometry3d& transform, const std::string& parent,
                                            const std::string& child, const ros::Time& stamp);

}  // namespace rigid_body_sim
