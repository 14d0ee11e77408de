#include "rigid_body_sim/ros/snapshot.h"

namespace rigid_body_sim {

SnapshotBuilder::SnapshotBuilder(std::string world_frame, std::string frame_prefix,
                                 const std::vector<Body>& bodies, MarkerOptions trail)
    : scene_(std::move(world_frame), std::move(frame_prefix), bodies, trail) {}

std::vector<geometry_msgs::TransformStamped> SnapshotBuilder::staticTransforms(const ros::Time& stamp) const {
  std::vector<geometry_msgs::TransformStamped> transforms;
  for (const auto& placement : scene_.placements()) {
    transforms.push_back(
        toTransform(placement.world_from_frame, scene_.worldFrame(), placement.frame, stamp));
  }
  return transforms;
}

geometry_msgs::TransformStamped SnapshotBuilder::transform(std::size_t i, const ros::Time& stamp,
                                                           const Body& body) const {
  const Eigen::Isometry3d world_from_body = scene_.placements()[i].world_from_frame * frameFromBody(body);
  return toTransform(world_from_body, scene_.worldFrame(), scene_.bodyFrame(body), stamp);
}

void SnapshotBuilder::appendTransforms(std::size_t i, const ros::Time& stamp, const Body& body,
                                       tf2_msgs::TFMessage& tf) const {
  tf.transforms.push_back(transform(i, stamp, body));
  const BodyPlacement& placement = scene_.placements()[i];
  if (placement.ground_frame.empty()) return;
  tf.transforms.push_back(
      toTransform(worldFromGround(placement, body), scene_.worldFrame(), placement.ground_frame, stamp));
}

StateMsg SnapshotBuilder::state(std::size_t i, double t, const ros::Time& stamp, const Body& body) const {
  StateMsg state = toStateMsg(t, body);
  std::visit(
      [&](auto& msg) {
        msg.header.stamp = stamp;
        msg.header.frame_id = scene_.placements()[i].frame;
      },
      state);
  return state;
}

Snapshot SnapshotBuilder::build(double t, const ros::Time& stamp, const std::vector<Body>& bodies) const {
  Snapshot snapshot;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    appendTransforms(i, stamp, bodies[i], snapshot.tf);
    snapshot.states.push_back(state(i, t, stamp, bodies[i]));
  }
  return snapshot;
}

}  // namespace rigid_body_sim
