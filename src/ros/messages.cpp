#include "rigid_body_sim/ros/messages.h"

#include <cstdint>
#include <vector>

#include <ros/serialization.h>
#include <std_msgs/Header.h>

#include "rigid_body_sim/core/state_fields.h"

namespace rigid_body_sim {

ros::Time simStamp(double t) { return ros::Time(0, 1) + ros::Duration(t); }

namespace {

// Fills a state message through its serialized form, header, t, then the body's fields in the order of its
// table (core/state_fields.h), which is the message's (test_messages checks names, order and types): so
// that no field is named here. The caller sets the header.
template <class Msg, class Model>
Msg stateMsgOf(double t, const Model& model) {
  namespace ser = ros::serialization;
  const auto& table = stateFieldTable(model);
  const auto fields = stateFields(model);
  const std_msgs::Header header;
  std::uint32_t size = ser::serializationLength(header) + ser::serializationLength(t);
  for (std::size_t i = 0; i < fields.size(); ++i) {
    size +=
        table[i].text ? ser::serializationLength(fields[i].text) : ser::serializationLength(fields[i].number);
  }
  std::vector<std::uint8_t> buffer(size);
  ser::OStream out(buffer.data(), size);
  ser::serialize(out, header);
  ser::serialize(out, t);
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (table[i].text) {
      ser::serialize(out, fields[i].text);
    } else {
      ser::serialize(out, fields[i].number);
    }
  }
  Msg msg;
  ser::IStream in(buffer.data(), size);
  ser::deserialize(in, msg);
  return msg;
}

}  // namespace

RodState toRodStateMsg(double t, const Rod& rod) { return stateMsgOf<RodState>(t, rod); }

RollerState toRollerStateMsg(double t, const Roller& roller) { return stateMsgOf<RollerState>(t, roller); }

StateMsg toStateMsg(double t, const Body& body) {
  if (const auto* rod = std::get_if<Rod>(&body.model)) return toRodStateMsg(t, *rod);
  return toRollerStateMsg(t, std::get<Roller>(body.model));
}

geometry_msgs::Point toPoint(const Eigen::Vector3d& point) {
  geometry_msgs::Point msg;
  msg.x = point.x();
  msg.y = point.y();
  msg.z = point.z();
  return msg;
}

geometry_msgs::Pose toPose(const Eigen::Isometry3d& transform) {
  geometry_msgs::Pose pose;
  const Eigen::Quaterniond q(transform.rotation());
  pose.position = toPoint(transform.translation());
  pose.orientation.x = q.x();
  pose.orientation.y = q.y();
  pose.orientation.z = q.z();
  pose.orientation.w = q.w();
  return pose;
}

geometry_msgs::TransformStamped toTransform(const Eigen::Isometry3d& transform, const std::string& parent,
                                            const std::string& child, const ros::Time& stamp) {
  geometry_msgs::TransformStamped msg;
  msg.header.stamp = stamp;
  msg.header.frame_id = parent;
  msg.child_frame_id = child;
  const geometry_msgs::Pose pose = toPose(transform);
  msg.transform.translation.x = pose.position.x;
  msg.transform.translation.y = pose.position.y;
  msg.transform.translation.z = pose.position.z;
  msg.transform.rotation = pose.orientation;
  return msg;
}

}  // namespace rigid_body_sim
