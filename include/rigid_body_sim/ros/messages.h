// Core state -> ROS messages: the state messages, events, stamps, and Eigen poses as geometry messages.
#pragma once

#include <cstddef>
#include <string>
#include <type_traits>
#include <variant>

#include <geometry_msgs/Point.h>
#include <geometry_msgs/Pose.h>
#include <geometry_msgs/TransformStamped.h>
#include <ros/serialization.h>
#include <ros/time.h>
#include <std_msgs/Header.h>
#include <Eigen/Geometry>

#include "rigid_body_sim/Event.h"
#include "rigid_body_sim/core/state_fields.h"
#include "rigid_body_sim/core/world.h"
#include "rigid_body_sim/ros/body_types_ros.h"

namespace rigid_body_sim {

// Simulated time as a ROS stamp: t plus 1 ns, so that the t = 0 sample is a valid, non-zero time.
ros::Time simStamp(double t);

namespace detail {

// Fills a state message field by field in its .msg's order, as its generated serializer visits them: t, then
// the type's state fields (core/state_fields.h) in their table's order, which the build checks the .msg
// against (describe_body_types --check-messages). The header is left to the caller.
template <class Fields>
class StateMsgFiller {
 public:
  StateMsgFiller(double t, const Fields& fields) : t_(t), fields_(fields) {}
  void next(std_msgs::Header&) {}
  void next(double& value) { value = t_done_ ? fields_.at(next_++).number : (t_done_ = true, t_); }
  void next(std::string& text) { text = fields_.at(next_++).text; }

 private:
  double t_;
  const Fields& fields_;
  bool t_done_ = false;
  std::size_t next_ = 0;
};

}  // namespace detail

// A body's state message: the fields of its type's one table (core/state_fields.h), header left empty.
template <class Model, class = std::enable_if_t<!std::is_same_v<Model, Body>>>
auto toStateMsg(double t, const Model& model) {
  using Msg = typename RosMessages<TypeOfModel<Model>>::StateMsg;
  const auto fields = stateFields(model);
  detail::StateMsgFiller<decltype(fields)> filler(t, fields);
  Msg msg;
  ros::serialization::Serializer<Msg>::template allInOne<decltype(filler), Msg&>(filler, msg);
  return msg;
}
StateMsg toStateMsg(double t, const Body& body);

// An event as published on ~events and recorded (rigid_body_sim/Event), stamped `stamp` (its instant).
rigid_body_sim::Event toEventMsg(const BodyEvent& event, const ros::Time& stamp);

geometry_msgs::Point toPoint(const Eigen::Vector3d& point);
geometry_msgs::Pose toPose(const Eigen::Isometry3d& transform);
geometry_msgs::TransformStamped toTransform(const Eigen::Isometry3d& transform, const std::string& parent,
                                            const std::string& child, const ros::Time& stamp);

}  // namespace rigid_body_sim
