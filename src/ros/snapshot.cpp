#include "rigid_body_sim/ros/snapshot.h"

namespace rigid_body_sim {

SnapshotBuilder::SnapshotBuilder(std::string world_frame, std::string frame_prefix,
                                 const std::vector<Body>& bodies, TrailOptions trail)
    : scene_(std::move(world_frame), std::move(frame_prefix), bodies, trail) {}

std::vector<geometry_msgs::TransformStamped> SnapshotBuilder::staticTransforms(const ros::Time& stamp) const {
  std::vector<geometry_msgs::TransformStamped> transforms;
  for (const auto& placement : scene_.placements()) {
    transforms.push_back(
        toTransform(placement.world_from_frame, scene_.worldFrame(), placement.frame, stamp));
  }
  return transforms;
}

Snapshot SnapshotBuilder::build(double t, const ros::Time& stamp, const std::vector<Body>& bodies) const {
  Snapshot snapshot;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body& body = bodies[i];
    const BodyPlacement& placement = scene_.placements()[i];
    const Eigen::Isometry3d world_from_body = placement.world_from_frame * frameFromBody(body);
    snapshot.tf.transforms.push_back(
        toTransform(world_from_body, scene_.worldFrame(), scene_.bodyFrame(body), stamp));
    snapshot.states.push_back(toStateMsg(t, body));
    std::visit(
        [&](auto& msg) {
          msg.header.stamp = stamp;
          msg.header.frame_id = placement.frame;
        },
        snapshot.states.back());
  }
  return snapshot;
}

}  // namespace rigid_body_sim
