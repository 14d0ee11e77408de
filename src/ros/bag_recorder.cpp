#include "rigid_body_sim/ros/bag_recorder.h"

#include <cstdio>

#include <boost/make_shared.hpp>

#include "rigid_body_sim/io/node_interface.h"

namespace rigid_body_sim {

namespace {

std::string stateTopic(const std::string& node_namespace, const std::string& body) {
  return node_namespace + "/" + node_interface::stateTopic(body);
}

std::string markerTopic(const std::string& node_namespace) {
  return node_namespace + "/" + node_interface::kMarkers;
}

}  // namespace

BagRecorder::BagRecorder(const std::string& path, const std::string& world_frame,
                         const std::vector<Body>& bodies, std::string node_namespace)
    : path_(path), node_namespace_(std::move(node_namespace)), snapshots_(world_frame, "", bodies) {
  bag_.open(path_ + ".active", rosbag::bagmode::Write);
  open_ = true;
  // /tf_static is latched: a player hands it to late subscribers as a live node would.
  // rosbag stores a given connection header as it is: without type, md5sum and definition, Python's
  // rosbag (rosbag info, scripts) cannot read the bag.
  auto latched = boost::make_shared<ros::M_string>();
  (*latched)["type"] = ros::message_traits::datatype<tf2_msgs::TFMessage>();
  (*latched)["md5sum"] = ros::message_traits::md5sum<tf2_msgs::TFMessage>();
  (*latched)["message_definition"] = ros::message_traits::definition<tf2_msgs::TFMessage>();
  (*latched)["latching"] = "1";
  (*latched)["callerid"] = node_namespace_;
  const ros::Time start = simStamp(0.0);
  tf2_msgs::TFMessage message;
  message.transforms = snapshots_.staticTransforms(start);
  bag_.write("/tf_static", start, message, latched);
  bag_.write(markerTopic(node_namespace_), start, snapshots_.staticMarkers(start));
}

BagRecorder::~BagRecorder() {
  // An unfinished recording stays as <path>.active, the way `rosbag record` leaves one.
  if (open_) bag_.close();
}

void BagRecorder::write(const World& world) {
  const double t = world.time();
  const ros::Time stamp = simStamp(t);
  const Snapshot snapshot = snapshots_.build(t, stamp, world.bodies());
  bag_.write("/tf", stamp, snapshot.tf);
  bag_.write(markerTopic(node_namespace_), stamp, snapshot.markers);
  for (std::size_t i = 0; i < world.bodies().size(); ++i) {
    const std::string topic = stateTopic(node_namespace_, world.bodies()[i].name);
    std::visit([&](const auto& msg) { bag_.write(topic, stamp, msg); }, snapshot.states[i]);
  }
}

void BagRecorder::commit() {
  if (!open_) return;
  bag_.close();
  open_ = false;
  if (std::rename((path_ + ".active").c_str(), path_.c_str()) != 0) {
    throw rosbag::BagException("cannot rename '" + path_ + ".active' to '" + path_ + "'");
  }
}

std::unique_ptr<SampleSink> openBag(const std::string& path, const WorldConfig& config,
                                    const std::vector<Body>& bodies) {
  return std::make_unique<BagRecorder>(path, config.world_frame, bodies);
}

}  // namespace rigid_body_sim
