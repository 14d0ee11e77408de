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

}  // namespace rigid_body_sim
