#include "rigid_body_sim/ros/messages.h"

namespace rigid_body_sim {

ros::Time simStamp(double t) { return ros::Time(0, 1) + ros::Duration(t); }

StateMsg toStateMsg(double t, const Body& body) {
  return std::visit([t](const auto& model) -> StateMsg { return toStateMsg(t, model); }, body.model);
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

namespace {
std::vector<rigid_body_sim::EventField> toValueMsgs(const std::vector<EventValue>& values) {
  std::vector<rigid_body_sim::EventField> out(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    out[i].name = values[i].name;
    out[i].number = values[i].number;
    out[i].text = values[i].text;
  }
  return out;
}
}  // namespace

rigid_body_sim::Event toEventMsg(const BodyEvent& event, const ros::Time& stamp) {
  rigid_body_sim::Event message;
  message.header.stamp = stamp;
  message.t = event.t;
  message.body = event.body;
  message.type = event.type;
  message.kind = event.kind;
  message.state = toValueMsgs(event.state);
  message.values = toValueMsgs(event.values);
  return message;
}

}  // namespace rigid_body_sim
